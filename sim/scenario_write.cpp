// Scenario -> YAML with every default written out. Numbers use the shortest text that
// reads back to the same double (std::to_chars), so Load(ToYaml(s)) == s exactly.
#include <charconv>

#include "sim/scenario_yaml.hpp"

namespace slambox {
namespace {

std::string Num(double v) {
  char buf[64];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof(buf), v);
  return std::string(buf, end);
}

template <class T>
YAML::EMITTER_MANIP FlowIfEmpty(const std::vector<T>& items) {
  return items.empty() ? YAML::Flow : YAML::Block;
}

void EmitPoint(YAML::Emitter& out, const Eigen::Vector2d& p) {
  out << YAML::Flow << YAML::BeginSeq << Num(p.x()) << Num(p.y()) << YAML::EndSeq;
}

void EmitPoints(YAML::Emitter& out, const std::vector<Eigen::Vector2d>& points) {
  out << YAML::Flow << YAML::BeginSeq;
  for (const auto& p : points) EmitPoint(out, p);
  out << YAML::EndSeq;
}

void EmitPose(YAML::Emitter& out, const PoseSpec& p) {
  out << YAML::Flow << YAML::BeginMap << YAML::Key << "x" << YAML::Value << Num(p.x) << YAML::Key << "y"
      << YAML::Value << Num(p.y) << YAML::Key << "theta_deg" << YAML::Value << Num(p.theta_deg) << YAML::EndMap;
}

// Key-value helpers for flow maps.
struct KV {
  YAML::Emitter& out;
  KV& operator()(const char* key, double v) {
    out << YAML::Key << key << YAML::Value << Num(v);
    return *this;
  }
  KV& operator()(const char* key, int v) {
    out << YAML::Key << key << YAML::Value << v;
    return *this;
  }
  KV& operator()(const char* key, bool v) {
    out << YAML::Key << key << YAML::Value << (v ? "true" : "false");
    return *this;
  }
};

void EmitWall(YAML::Emitter& out, const WallSpec& w) {
  out << YAML::Flow << YAML::BeginMap;
  switch (w.kind) {
    case WallSpec::Kind::kPolyline:
    case WallSpec::Kind::kPolygon:
      out << YAML::Key << (w.kind == WallSpec::Kind::kPolyline ? "polyline" : "polygon") << YAML::Value;
      EmitPoints(out, w.points);
      break;
    case WallSpec::Kind::kBox:
      out << YAML::Key << "box" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "center" << YAML::Value;
      EmitPoint(out, w.center);
      out << YAML::Key << "size" << YAML::Value;
      EmitPoint(out, w.size);
      KV{out}("angle_deg", w.angle_deg);
      out << YAML::EndMap;
      break;
    case WallSpec::Kind::kCircle:
      out << YAML::Key << "circle" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "center"
          << YAML::Value;
      EmitPoint(out, w.center);
      KV{out}("radius_m", w.radius_m);
      out << YAML::EndMap;
      break;
  }
  out << YAML::EndMap;
}

void EmitMover(YAML::Emitter& out, const MoverSpec& m) {
  out << YAML::Flow << YAML::BeginMap;
  if (m.is_box) {
    out << YAML::Key << "box" << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "size" << YAML::Value;
    EmitPoint(out, m.size);
    out << YAML::EndMap;
  } else {
    out << YAML::Key << "circle" << YAML::Value << YAML::Flow << YAML::BeginMap;
    KV{out}("radius_m", m.radius_m);
    out << YAML::EndMap;
  }
  out << YAML::Key << "path" << YAML::Value;
  EmitPoints(out, m.path);
  KV{out}("speed_mps", m.speed_mps)("loop", m.loop);
  out << YAML::EndMap;
}

void EmitSensors(YAML::Emitter& out, const SensorSuite& s) {
  out << YAML::Key << "sensors" << YAML::Value << YAML::BeginMap;
  if (const auto& o = s.odometry) {
    out << YAML::Key << "odometry" << YAML::Value << YAML::Flow << YAML::BeginMap;
    KV{out}("rate_hz", o->rate_hz);
    out << YAML::Key << "alpha" << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (double a : o->alpha) out << Num(a);
    out << YAML::EndSeq << YAML::EndMap;
  }
  if (const auto& l = s.lidar) {
    out << YAML::Key << "lidar" << YAML::Value << YAML::Flow << YAML::BeginMap;
    KV{out}("rate_hz", l->rate_hz)("beams", l->beams)("fov_deg", l->fov_deg)("range_min_m", l->range_min_m)(
        "range_max_m", l->range_max_m)("sigma_range_m", l->sigma_range_m)("sigma_bearing_deg", l->sigma_bearing_deg)(
        "dropout_prob", l->dropout_prob);
    out << YAML::EndMap;
  }
  if (const auto& l = s.landmarks) {
    out << YAML::Key << "landmarks" << YAML::Value << YAML::Flow << YAML::BeginMap;
    KV{out}("rate_hz", l->rate_hz)("range_max_m", l->range_max_m)("fov_deg", l->fov_deg)("sigma_range_m",
                                                                                          l->sigma_range_m)(
        "sigma_bearing_deg", l->sigma_bearing_deg)("known_ids", l->known_ids)("detection_prob", l->detection_prob)(
        "detection_prob_known", l->detection_prob_known)(
        "clutter_per_scan", l->clutter_per_scan);
    out << YAML::EndMap;
  }
  if (const auto& g = s.gyro) {
    out << YAML::Key << "gyro" << YAML::Value << YAML::Flow << YAML::BeginMap;
    KV{out}("rate_hz", g->rate_hz)("sigma_dps", g->sigma_dps)("bias_dps", g->bias_dps);
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
}

}  // namespace

std::string ScenarioToYaml(const Scenario& s) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "version" << YAML::Value << s.version;
  out << YAML::Key << "name" << YAML::Value << s.name;
  out << YAML::Key << "description" << YAML::Value << s.description;
  KV{out}("duration_s", s.duration_s);

  out << YAML::Key << "world" << YAML::Value << YAML::BeginMap;
  if (!s.occupancy_map.empty()) out << YAML::Key << "occupancy_map" << YAML::Value << s.occupancy_map;
  out << YAML::Key << "walls" << YAML::Value << FlowIfEmpty(s.walls) << YAML::BeginSeq;
  for (const auto& w : s.walls) EmitWall(out, w);
  out << YAML::EndSeq << YAML::Key << "landmarks" << YAML::Value << FlowIfEmpty(s.landmarks) << YAML::BeginSeq;
  for (const auto& l : s.landmarks) {
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "pos" << YAML::Value;
    EmitPoint(out, l.pos);
    KV{out}("radius_m", l.radius_m)("id", l.id);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::Key << "movers" << YAML::Value << FlowIfEmpty(s.movers) << YAML::BeginSeq;
  for (const auto& m : s.movers) EmitMover(out, m);
  out << YAML::EndSeq << YAML::EndMap;

  const RobotSpec& r = s.robot;
  out << YAML::Key << "robot" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "start" << YAML::Value;
  EmitPose(out, r.start);
  KV{out}("radius_m", r.radius_m)("max_speed_mps", r.max_speed_mps)("max_turn_rate_deg_s", r.max_turn_rate_deg_s);
  out << YAML::Key << "path" << YAML::Value << YAML::BeginSeq;
  for (const auto& p : r.path) EmitPoint(out, p);
  out << YAML::EndSeq;
  KV{out}("laps", r.laps);
  if (r.kidnap) {
    out << YAML::Key << "kidnap" << YAML::Value << YAML::Flow << YAML::BeginMap;
    KV{out}("at_s", r.kidnap->at_s);
    out << YAML::Key << "to" << YAML::Value;
    EmitPose(out, r.kidnap->to);
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
  EmitSensors(out, s.sensors);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace slambox
