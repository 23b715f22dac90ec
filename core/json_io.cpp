#include "core/json_io.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "core/error.hpp"

#include <cmath>

namespace slambox {

nlohmann::json ReadJsonFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "cannot open the file", "check the path; `slambox run` writes it");
  std::stringstream buf;
  buf << in.rdbuf();
  const std::string text = buf.str();
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    const size_t upto = std::min(text.size(), static_cast<size_t>(e.byte));
    const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + upto, '\n'));
    throw InputError(path, line, std::string("malformed JSON: ") + e.what(), "re-run the command that wrote it");
  }
}

using nlohmann::json;

namespace {
json Num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }
double NumOr(const json& j, double fallback = std::nan("")) { return j.is_number() ? j.get<double>() : fallback; }
json Vec2(const Eigen::Vector2d& v) { return json::array({Num(v.x()), Num(v.y())}); }
Eigen::Vector2d Vec2From(const json& j) { return {NumOr(j.at(0)), NumOr(j.at(1))}; }
template <int N>
json Mat(const Eigen::Matrix<double, N, N>& m) {
  json a = json::array();
  for (int r = 0; r < N; ++r)
    for (int c = 0; c < N; ++c) a.push_back(Num(m(r, c)));
  return a;
}
template <int N>
Eigen::Matrix<double, N, N> MatFrom(const json& j) {
  Eigen::Matrix<double, N, N> m;
  for (int r = 0; r < N; ++r)
    for (int c = 0; c < N; ++c) m(r, c) = NumOr(j.at(r * N + c));
  return m;
}
}  // namespace

json ToJson(const SE2& p) { return json::array({Num(p.x), Num(p.y), Num(p.theta)}); }
SE2 SE2FromJson(const json& j) {
  SE2 p;
  p.x = NumOr(j.at(0));
  p.y = NumOr(j.at(1));
  p.theta = NumOr(j.at(2));
  return p;
}

json ToJson(const World& w) {
  json j;
  j["wall_segments"] = json::array();
  for (const auto& s : w.wall_segments) j["wall_segments"].push_back({Vec2(s.a), Vec2(s.b)});
  j["wall_circles"] = json::array();
  for (const auto& c : w.wall_circles) j["wall_circles"].push_back({{"center", Vec2(c.center)}, {"radius_m", c.radius_m}});
  j["landmarks"] = json::array();
  for (const auto& l : w.landmarks)
    j["landmarks"].push_back({{"id", l.id}, {"pos", Vec2(l.position)}, {"radius_m", l.radius_m}});
  j["movers"] = json::array();
  for (const auto& m : w.movers) {
    json path = json::array();
    for (const auto& p : m.path) path.push_back(Vec2(p));
    j["movers"].push_back({{"path", path}, {"radius_m", m.radius_m}, {"box_size_m", Vec2(m.box_size_m)}});
  }
  return j;
}

World WorldFromJson(const json& j) {
  World w;
  for (const auto& s : j.at("wall_segments")) w.wall_segments.push_back({Vec2From(s.at(0)), Vec2From(s.at(1))});
  for (const auto& c : j.at("wall_circles")) w.wall_circles.push_back({Vec2From(c.at("center")), c.at("radius_m").get<double>()});
  for (const auto& l : j.at("landmarks"))
    w.landmarks.push_back({l.at("id").get<int>(), Vec2From(l.at("pos")), l.at("radius_m").get<double>()});
  for (const auto& m : j.at("movers")) {
    MoverTrack t;
    for (const auto& p : m.at("path")) t.path.push_back(Vec2From(p));
    t.radius_m = m.at("radius_m").get<double>();
    t.box_size_m = Vec2From(m.at("box_size_m"));
    w.movers.push_back(t);
  }
  return w;
}

json ToJson(const Estimate& e) {
  json j;
  json traj = json::array();
  for (const auto& p : e.trajectory) {
    json item = {{"t", p.t_s}, {"pose", ToJson(p.pose)}};
    if (p.has_covariance) item["cov"] = Mat<3>(p.covariance);
    traj.push_back(item);
  }
  j["trajectory"] = traj;
  json lms = json::array();
  for (const auto& l : e.landmarks) {
    json item = {{"id", l.id}, {"pos", Vec2(l.position)}};
    if (l.has_covariance) item["cov"] = Mat<2>(l.covariance);
    lms.push_back(item);
  }
  j["landmarks"] = lms;
  json pts = json::array();
  for (const auto& p : e.map_points) pts.push_back(Vec2(p));
  j["map_points"] = pts;
  if (e.grid) {
    const auto& g = *e.grid;
    j["grid"] = {{"origin_m", Vec2(g.origin_m)}, {"resolution_m", g.resolution_m}, {"width", g.width},
                 {"height", g.height}, {"cells", g.cells}};
  }
  json lcs = json::array();
  for (const auto& c : e.loop_closures)
    lcs.push_back({{"t_from", c.t_from_s}, {"t_to", c.t_to_s}, {"T_from_to", ToJson(c.T_from_to)}, {"accepted", c.accepted}});
  j["loop_closures"] = lcs;
  json nodes = json::array();
  for (size_t i = 0; i < e.pose_graph.nodes.size(); ++i)
    nodes.push_back({{"t", e.pose_graph.node_t_s.at(i)}, {"pose", ToJson(e.pose_graph.nodes[i])}});
  json edges = json::array();
  for (const auto& ed : e.pose_graph.edges)
    edges.push_back({{"from", ed.from}, {"to", ed.to}, {"loop_closure", ed.loop_closure}, {"accepted", ed.accepted}});
  j["pose_graph"] = {{"nodes", nodes}, {"edges", edges}};
  json parts = json::array();
  for (const auto& s : e.particles) {
    json poses = json::array();
    for (const auto& p : s.poses) poses.push_back(ToJson(p));
    parts.push_back({{"t", s.t_s}, {"poses", poses}, {"weights", s.weights}});
  }
  j["particles"] = parts;
  json diag = json::object();
  for (const auto& [name, series] : e.diagnostics) {
    json s = json::array();
    for (const auto& [t, v] : series) s.push_back({t, Num(v)});
    diag[name] = s;
  }
  j["diagnostics"] = diag;
  // [scan, index, landmark, created]; left out when the module reports none (older files lack it).
  if (!e.observation_assignments.empty()) {
    json as = json::array();
    for (const auto& a : e.observation_assignments) as.push_back({a.scan, a.index, a.landmark, a.created ? 1 : 0});
    j["observation_assignments"] = as;
  }
  return j;
}

Estimate EstimateFromJson(const json& j) {
  Estimate e;
  for (const auto& item : j.at("trajectory")) {
    PoseEstimate p;
    p.t_s = item.at("t").get<double>();
    p.pose = SE2FromJson(item.at("pose"));
    if (item.contains("cov")) { p.covariance = MatFrom<3>(item.at("cov")); p.has_covariance = true; }
    e.trajectory.push_back(p);
  }
  for (const auto& item : j.at("landmarks")) {
    LandmarkEstimate l;
    l.id = item.at("id").get<int>();
    l.position = Vec2From(item.at("pos"));
    if (item.contains("cov")) { l.covariance = MatFrom<2>(item.at("cov")); l.has_covariance = true; }
    e.landmarks.push_back(l);
  }
  for (const auto& p : j.at("map_points")) e.map_points.push_back(Vec2From(p));
  if (j.contains("grid")) {
    const auto& g = j.at("grid");
    OccupancyGrid grid;
    grid.origin_m = Vec2From(g.at("origin_m"));
    grid.resolution_m = g.at("resolution_m").get<double>();
    grid.width = g.at("width").get<int>();
    grid.height = g.at("height").get<int>();
    grid.cells = g.at("cells").get<std::vector<std::int8_t>>();
    e.grid = grid;
  }
  for (const auto& c : j.at("loop_closures"))
    e.loop_closures.push_back({c.at("t_from").get<double>(), c.at("t_to").get<double>(), SE2FromJson(c.at("T_from_to")),
                               c.at("accepted").get<bool>()});
  for (const auto& n : j.at("pose_graph").at("nodes")) {
    e.pose_graph.node_t_s.push_back(n.at("t").get<double>());
    e.pose_graph.nodes.push_back(SE2FromJson(n.at("pose")));
  }
  for (const auto& ed : j.at("pose_graph").at("edges"))
    e.pose_graph.edges.push_back({ed.at("from").get<int>(), ed.at("to").get<int>(), ed.at("loop_closure").get<bool>(),
                                  ed.at("accepted").get<bool>()});
  for (const auto& s : j.at("particles")) {
    ParticleSnapshot snap;
    snap.t_s = s.at("t").get<double>();
    for (const auto& p : s.at("poses")) snap.poses.push_back(SE2FromJson(p));
    snap.weights = s.at("weights").get<std::vector<double>>();
    e.particles.push_back(snap);
  }
  for (const auto& [name, series] : j.at("diagnostics").items())
    for (const auto& tv : series) e.diagnostics[name].push_back({tv.at(0).get<double>(), NumOr(tv.at(1))});
  if (j.contains("observation_assignments"))
    for (const auto& a : j.at("observation_assignments"))
      e.observation_assignments.push_back(
          {a.at(0).get<int>(), a.at(1).get<int>(), a.at(2).get<int>(), a.at(3).get<int>() != 0});
  return e;
}

json ToJson(const SensorSuite& s) {
  json j = json::object();
  if (s.odometry) j["odometry"] = {{"rate_hz", s.odometry->rate_hz}, {"alpha", s.odometry->alpha}};
  if (s.lidar) {
    const auto& l = *s.lidar;
    j["lidar"] = {{"rate_hz", l.rate_hz}, {"beams", l.beams}, {"fov_deg", l.fov_deg}, {"range_min_m", l.range_min_m},
                  {"range_max_m", l.range_max_m}, {"sigma_range_m", l.sigma_range_m},
                  {"sigma_bearing_deg", l.sigma_bearing_deg}, {"dropout_prob", l.dropout_prob}};
  }
  if (s.landmarks) {
    const auto& l = *s.landmarks;
    j["landmarks"] = {{"rate_hz", l.rate_hz}, {"range_max_m", l.range_max_m}, {"fov_deg", l.fov_deg},
                      {"sigma_range_m", l.sigma_range_m}, {"sigma_bearing_deg", l.sigma_bearing_deg},
                      {"known_ids", l.known_ids}, {"detection_prob", l.detection_prob},
                      {"detection_prob_known", l.detection_prob_known},
                      {"clutter_per_scan", l.clutter_per_scan}};
  }
  if (s.gyro) j["gyro"] = {{"rate_hz", s.gyro->rate_hz}, {"sigma_dps", s.gyro->sigma_dps}, {"bias_dps", s.gyro->bias_dps}};
  return j;
}

SensorSuite SensorSuiteFromJson(const json& j) {
  SensorSuite s;
  if (j.contains("odometry")) {
    const auto& o = j.at("odometry");
    OdometryConfig c;
    c.rate_hz = o.value("rate_hz", c.rate_hz);
    c.alpha = o.value("alpha", c.alpha);
    s.odometry = c;
  }
  if (j.contains("lidar")) {
    const auto& l = j.at("lidar");
    LidarConfig c;
    c.rate_hz = l.value("rate_hz", c.rate_hz);
    c.beams = l.value("beams", c.beams);
    c.fov_deg = l.value("fov_deg", c.fov_deg);
    c.range_min_m = l.value("range_min_m", c.range_min_m);
    c.range_max_m = l.value("range_max_m", c.range_max_m);
    c.sigma_range_m = l.value("sigma_range_m", c.sigma_range_m);
    c.sigma_bearing_deg = l.value("sigma_bearing_deg", c.sigma_bearing_deg);
    c.dropout_prob = l.value("dropout_prob", c.dropout_prob);
    s.lidar = c;
  }
  if (j.contains("landmarks")) {
    const auto& l = j.at("landmarks");
    LandmarkSensorConfig c;
    c.rate_hz = l.value("rate_hz", c.rate_hz);
    c.range_max_m = l.value("range_max_m", c.range_max_m);
    c.fov_deg = l.value("fov_deg", c.fov_deg);
    c.sigma_range_m = l.value("sigma_range_m", c.sigma_range_m);
    c.sigma_bearing_deg = l.value("sigma_bearing_deg", c.sigma_bearing_deg);
    c.known_ids = l.value("known_ids", c.known_ids);
    c.detection_prob = l.value("detection_prob", c.detection_prob);
    c.detection_prob_known = l.value("detection_prob_known", c.detection_prob_known);
    c.clutter_per_scan = l.value("clutter_per_scan", c.clutter_per_scan);
    s.landmarks = c;
  }
  if (j.contains("gyro")) {
    const auto& g = j.at("gyro");
    GyroConfig c;
    c.rate_hz = g.value("rate_hz", c.rate_hz);
    c.sigma_dps = g.value("sigma_dps", c.sigma_dps);
    c.bias_dps = g.value("bias_dps", c.bias_dps);
    s.gyro = c;
  }
  return s;
}

}  // namespace slambox
