// Built-in scenarios load and have the properties their descriptions promise;
// show -> load round trips exactly; `--set` overrides change exactly what they name.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "core/error.hpp"
#include "sim/scenario.hpp"
#include "tests/sim/scenario_test_support.hpp"

namespace slambox {
namespace {

const std::vector<std::string> kBuiltins = {"dynamic", "forest", "landmarks", "loop", "maze", "office", "symmetric", "tunnel"};

/// Metres driven: start -> path, then (laps - 1) more times around the closed path.
double PathLength(const RobotSpec& r) {
  double one = 0.0, total = 0.0;
  Eigen::Vector2d at(r.start.x, r.start.y);
  for (const auto& p : r.path) {
    total += (p - at).norm();
    at = p;
  }
  for (std::size_t i = 0; i < r.path.size(); ++i) one += (r.path[(i + 1) % r.path.size()] - r.path[i]).norm();
  return total + (r.laps - 1) * one;
}

/// Points every `step_m` along the driven legs (start -> path, one lap).
std::vector<Eigen::Vector2d> Samples(const RobotSpec& r, double step_m) {
  std::vector<Eigen::Vector2d> out;
  Eigen::Vector2d at(r.start.x, r.start.y);
  for (const auto& p : r.path) {
    const int n = std::max(1, static_cast<int>((p - at).norm() / step_m));
    for (int k = 0; k < n; ++k) out.push_back(at + (p - at) * (static_cast<double>(k) / n));
    at = p;
  }
  return out;
}

/// Lower bound on the drive time of a turn-then-drive controller: distance / v_max plus
/// every heading change / turn rate.
double DriveTime(const RobotSpec& r) {
  std::vector<Eigen::Vector2d> pts = {Eigen::Vector2d(r.start.x, r.start.y)};
  for (int lap = 0; lap < r.laps; ++lap) pts.insert(pts.end(), r.path.begin(), r.path.end());
  double heading = r.start.theta_deg * M_PI / 180.0, turn_rad = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const Eigen::Vector2d d = pts[i] - pts[i - 1];
    if (d.norm() < 1e-9) continue;
    const double h = std::atan2(d.y(), d.x());
    turn_rad += std::abs(std::remainder(h - heading, 2 * M_PI));
    heading = h;
  }
  return PathLength(r) / r.max_speed_mps + turn_rad / (r.max_turn_rate_deg_s * M_PI / 180.0);
}

TEST(Scenario, BuiltinListHasTheSevenWithOneLineDescriptions) {
  std::vector<std::string> names;
  for (const auto& b : BuiltinScenarios()) {
    names.push_back(b.name);
    EXPECT_GT(b.description.size(), 20u) << b.name;
    EXPECT_EQ(b.description.find('\n'), std::string::npos) << b.name;
  }
  EXPECT_EQ(names, kBuiltins);
}

TEST(Scenario, EveryBuiltinLoadsWithHalfMetreClearanceAndModestDuration) {
  for (const auto& name : kBuiltins) {
    SCOPED_TRACE(name);
    const Scenario s = LoadScenario(name);
    EXPECT_EQ(s.name, name);
    EXPECT_EQ(s.source, "builtin:" + name);
    EXPECT_TRUE(s.sensors.odometry.has_value());
    // forest is the 400 m park of issue 14 (two laps of a 60 x 40 m rectangle); the rest stay short.
    EXPECT_LE(DriveTime(s.robot), name == "forest" ? 450.0 : 300.0);
    // The geometric check uses the robot's radius: a 0.75 m disc passing everywhere means
    // the real 0.25 m robot clears every wall and post by >= 0.5 m on every leg.
    EXPECT_EQ(s.robot.radius_m, 0.25);
    EXPECT_NO_THROW(LoadScenario(name, {"robot.radius_m=0.75"}));
  }
}

TEST(Scenario, BuiltinsHaveTheirPromisedShape) {
  const Scenario loop = LoadScenario("loop");
  EXPECT_EQ(loop.robot.laps, 2);
  const double lap_m = PathLength(loop.robot) / 2.0;
  EXPECT_GE(lap_m, 100.0);
  EXPECT_LE(lap_m, 200.0);
  ASSERT_TRUE(loop.sensors.lidar);
  EXPECT_EQ(loop.sensors.lidar->beams, 360);

  const Scenario tunnel = LoadScenario("tunnel");
  ASSERT_TRUE(tunnel.sensors.lidar);
  double min_x = 1e9, max_x = -1e9;
  for (const auto& p : tunnel.robot.path) min_x = std::min(min_x, p.x()), max_x = std::max(max_x, p.x());
  EXPECT_GE(max_x - min_x, 60.0);
  // The end walls (the outline's x extremes) are beyond lidar range over most of the drive.
  const auto& outline = tunnel.walls.at(0).points;
  double wall_lo = 1e9, wall_hi = -1e9;
  for (const auto& p : outline) wall_lo = std::min(wall_lo, p.x()), wall_hi = std::max(wall_hi, p.x());
  int blind = 0;
  const auto samples = Samples(tunnel.robot, 0.5);
  for (const auto& p : samples)
    blind += std::min(p.x() - wall_lo, wall_hi - p.x()) > tunnel.sensors.lidar->range_max_m;
  EXPECT_GT(blind, 0.6 * samples.size());

  const Scenario park = LoadScenario("landmarks");
  EXPECT_GE(park.landmarks.size(), 40u);
  EXPECT_TRUE(park.sensors.landmarks.has_value());
  EXPECT_FALSE(park.sensors.lidar.has_value());
  EXPECT_GE(PathLength(park.robot), 100.0);
  EXPECT_LE(PathLength(park.robot), 200.0);
  // At least 5 posts within detector range everywhere along the path (occlusion aside).
  for (const auto& p : Samples(park.robot, 0.5)) {
    int in_range = 0;
    for (const auto& l : park.landmarks) in_range += (l.pos - p).norm() <= park.sensors.landmarks->range_max_m;
    EXPECT_GE(in_range, 5) << p.transpose();
  }

  const Scenario dynamic = LoadScenario("dynamic");
  bool has_box = false, has_circle = false;
  for (const auto& m : dynamic.movers) (m.is_box ? has_box : has_circle) = true;
  EXPECT_TRUE(has_box && has_circle);
  const Scenario maze = LoadScenario("maze");
  EXPECT_TRUE(maze.sensors.lidar.has_value());
  // Doors: gaps between collinear axis-aligned wall pieces, all at least 1.2 m wide.
  std::map<std::pair<bool, double>, std::vector<std::pair<double, double>>> lines;
  for (const auto& w : maze.walls) {
    if (w.kind != WallSpec::Kind::kPolyline || w.points.size() != 2) continue;
    const Eigen::Vector2d a = w.points[0], b = w.points[1];
    const bool vertical = a.x() == b.x();
    const double along_a = vertical ? a.y() : a.x(), along_b = vertical ? b.y() : b.x();
    lines[{vertical, vertical ? a.x() : a.y()}].emplace_back(std::min(along_a, along_b), std::max(along_a, along_b));
  }
  int doors = 0;
  for (auto& [line, pieces] : lines) {
    std::sort(pieces.begin(), pieces.end());
    for (std::size_t i = 0; i + 1 < pieces.size(); ++i) {
      const double gap = pieces[i + 1].first - pieces[i].second;
      if (gap <= 0.0) continue;
      ++doors;
      EXPECT_GE(gap, 1.2) << "door on line " << line.second;
    }
  }
  EXPECT_GE(doors, 10);
}

TEST(Scenario, SymmetricWorldIsPointSymmetric) {
  // Every wall vertex / centre maps onto one of the world under p -> 2c - p.
  const Scenario s = LoadScenario("symmetric");
  std::vector<Eigen::Vector2d> pts;
  for (const auto& w : s.walls) {
    if (w.kind == WallSpec::Kind::kPolyline || w.kind == WallSpec::Kind::kPolygon)
      pts.insert(pts.end(), w.points.begin(), w.points.end());
    else
      pts.push_back(w.center);
  }
  Eigen::Vector2d lo = pts[0], hi = pts[0];
  for (const auto& p : pts) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const Eigen::Vector2d c = 0.5 * (lo + hi);
  for (const auto& p : pts) {
    double best = 1e9;
    for (const auto& q : pts) best = std::min(best, (2 * c - p - q).norm());
    EXPECT_LT(best, 1e-9) << p.transpose();
  }
}

TEST(Scenario, ShowThenLoadRoundTripsExactly) {
  testing::TempDir dir;
  for (const auto& name : kBuiltins) {
    SCOPED_TRACE(name);
    const Scenario a = LoadScenario(name);
    const std::string yaml = ScenarioToYaml(a);
    const Scenario b = LoadScenario(dir.Write(name + ".yaml", yaml));
    testing::ExpectSameScenario(a, b);
    EXPECT_EQ(ScenarioToYaml(b), yaml);
  }
  // Values without a short decimal form, a kidnap and a gyro survive too.
  const Scenario a = LoadScenario("loop", {"robot.radius_m=0.30000000000000004", "sensors.lidar.sigma_range_m=1e-7",
                                           "robot.kidnap={at_s: 60.5, to: {x: 20, y: 5.5, theta_deg: -33.3}}",
                                           "sensors.gyro={rate_hz: 100, bias_dps: 0.1}", "duration_s=123.456",
                                           "sensors.landmarks.detection_prob_known=false"});
  const Scenario b = LoadScenario(dir.Write("odd.yaml", ScenarioToYaml(a)));
  testing::ExpectSameScenario(a, b);
  EXPECT_FALSE(b.sensors.landmarks->detection_prob_known);
  EXPECT_EQ(b.robot.radius_m, 0.1 + 0.2);
}

TEST(Scenario, LoadFromTextGivesTheSameAsFromItsFile) {
  // A stream header stores ScenarioToYaml(); LoadScenarioText reads it back.
  const Scenario a = LoadScenario("dynamic");
  const Scenario b = LoadScenarioText(ScenarioToYaml(a), "stream header", {"robot.laps=1"});
  EXPECT_EQ(b.robot.laps, 1);
  EXPECT_EQ(b.source, "stream header");
  EXPECT_EQ(b.movers.size(), a.movers.size());
  try {
    LoadScenarioText("version: 3\nrobot: {path: [[1, 0]]}\n", "stream header");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("stream header:1: unsupported scenario version 3"), std::string::npos) << e.what();
  }
}

TEST(Scenario, ShowFillsEveryDefault) {
  testing::TempDir dir;
  const Scenario s = LoadScenario(dir.Write("min.yaml",
                                            "version: 1\nrobot: {path: [[1, 0]]}\nsensors: {lidar: {beams: 90}, "
                                            "odometry: {}, landmarks: {}, gyro: {}}\n"));
  EXPECT_EQ(s.name, "min");  // from the file name
  const std::string yaml = ScenarioToYaml(s);
  for (const char* key : {"duration_s:", "radius_m: 0.25", "max_speed_mps: 1", "max_turn_rate_deg_s: 90", "laps: 1",
                          "alpha: [0.05, 0.005, 0.05, 0.005]", "beams: 90", "range_max_m: 30", "sigma_range_m: 0.01",
                          "dropout_prob: 0", "known_ids: true", "clutter_per_scan: 0", "sigma_dps: 0.1", "walls: []"})
    EXPECT_NE(yaml.find(key), std::string::npos) << key << " missing in\n" << yaml;
  EXPECT_EQ(s.sensors.lidar->range_max_m, LidarConfig{}.range_max_m);
  EXPECT_EQ(s.sensors.landmarks->sigma_bearing_deg, LandmarkSensorConfig{}.sigma_bearing_deg);
  // No sensors block: no sensors.
  const Scenario bare = LoadScenario(dir.Write("bare.yaml", "version: 1\nrobot: {path: [[1, 0]]}\n"));
  EXPECT_FALSE(bare.sensors.odometry || bare.sensors.lidar || bare.sensors.landmarks || bare.sensors.gyro);
}

TEST(Scenario, OverridesChangeExactlyTheNamedKey) {
  const Scenario base = LoadScenario("loop");
  Scenario s = LoadScenario("loop", {"robot.laps=3", "sensors.lidar.sigma_range_m=0.05"});
  EXPECT_EQ(s.robot.laps, 3);
  EXPECT_EQ(s.sensors.lidar->sigma_range_m, 0.05);
  s.robot.laps = base.robot.laps;
  s.sensors.lidar->sigma_range_m = base.sensors.lidar->sigma_range_m;
  testing::ExpectSameScenario(s, base);

  // Remove a sensor block, add one (a key of an absent block creates it with defaults).
  const Scenario t = LoadScenario("loop", {"sensors.lidar=null", "sensors.gyro.rate_hz=100"});
  EXPECT_FALSE(t.sensors.lidar.has_value());
  ASSERT_TRUE(t.sensors.gyro.has_value());
  EXPECT_EQ(t.sensors.gyro->rate_hz, 100.0);
  EXPECT_EQ(t.sensors.gyro->sigma_dps, GyroConfig{}.sigma_dps);

  // List items by index, whole values as YAML.
  const Scenario u = LoadScenario("landmarks", {"world.landmarks.3.radius_m=0.2", "robot.path.0=[39, 10]",
                                                "sensors.landmarks.known_ids=false"});
  EXPECT_EQ(u.landmarks[3].radius_m, 0.2);
  EXPECT_EQ(u.robot.path[0], Eigen::Vector2d(39, 10));
  EXPECT_FALSE(u.sensors.landmarks->known_ids);
  // Later overrides win.
  EXPECT_EQ(LoadScenario("tunnel", {"robot.laps=2", "robot.laps=4"}).robot.laps, 4);
}

void ExpectOverrideError(const std::vector<std::string>& overrides, const std::string& problem, const std::string& fix) {
  testing::TempDir dir;
  const std::string file = dir.Write("s.yaml", "version: 1\nrobot:\n  path: [[1, 0]]\n  laps: 1\n");
  try {
    LoadScenario(file, overrides);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(file + " (--set " + overrides.back() + ")"), std::string::npos) << msg;
    EXPECT_EQ(e.line(), 0);  // an override has no line; the message names it instead
    EXPECT_NE(msg.find(problem), std::string::npos) << msg;
    EXPECT_NE(msg.find("\n  fix: "), std::string::npos) << msg;
    EXPECT_NE(msg.find(fix), std::string::npos) << msg;
  }
}

TEST(Scenario, BadOverrideKeysAndValues) {
  ExpectOverrideError({"robot.lapz=2"}, "unknown scenario key 'robot.lapz'", "start, radius_m, max_speed_mps");
  ExpectOverrideError({"sensors.lidar.beamz=2"}, "'sensors.lidar' has no key 'beamz'", "beams");
  ExpectOverrideError({"robotx=1"}, "the top level has no key 'robotx'", "version, name");
  ExpectOverrideError({"robot.laps.x=1"}, "'robot.laps' is a value", "--set robot.laps=VALUE");
  ExpectOverrideError({"robot.path.5=[1, 1]"}, "'robot.path' is a list of 1 items", "index 0..0");
  ExpectOverrideError({"robot.laps"}, "must look like key=value", "--set robot.laps=3");
  ExpectOverrideError({"algo.ekf-slam.gate=3"}, "is an algorithm parameter", "slambox run");
  ExpectOverrideError({"robot.laps=[1"}, "the value '[1' is not valid YAML", "quote it");
  ExpectOverrideError({"robot.laps=0"}, "robot.laps = 0 is out of range", ">= 1");
  ExpectOverrideError({"robot.laps=two"}, "robot.laps must be an integer, got 'two'", "");
  ExpectOverrideError({"sensors.lidar={beams: 0}"}, "sensors.lidar.beams = 0 is out of range", ">= 1");
  ExpectOverrideError({"sensors.lidar={bems: 10}"}, "unknown key 'bems' in sensors.lidar", "beams");
  ExpectOverrideError({"robot.laps=2", "version=2"}, "unsupported scenario version 2", "version: 1");
}

TEST(Scenario, LandmarkIdsDefaultToIndex) {
  testing::TempDir dir;
  const Scenario s = LoadScenario(dir.Write("ids.yaml",
                                            "version: 1\nworld:\n  landmarks:\n    - {pos: [5, 5]}\n    - {pos: [6, 5], "
                                            "id: 7}\n    - {pos: [7, 5]}\nrobot: {path: [[1, 0]]}\n"));
  ASSERT_EQ(s.landmarks.size(), 3u);
  EXPECT_EQ(s.landmarks[0].id, 0);
  EXPECT_EQ(s.landmarks[1].id, 7);
  EXPECT_EQ(s.landmarks[2].id, 2);
}

}  // namespace
}  // namespace slambox
