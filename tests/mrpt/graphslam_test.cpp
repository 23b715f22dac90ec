// mrpt-graphslam: its defaults are what MRPT's installed laser_odometry_LC.ini says (read
// with MRPT's own reader at run time, not copied); the engine's file is that text with the
// module's values written over it; in a room with drifty odometry it gives a finite pose
// at every scan, deterministic for a stream, and clearly better than dead reckoning.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "core/error.hpp"
#include "slam/mrpt/mrpt_graphslam.hpp"
#include "tests/mrpt/mrpt_test_support.hpp"
#include "tests/support/accuracy_bound.hpp"
#include "tests/support/slambox_cli.hpp"

namespace slambox::testing {
namespace {

namespace fs = std::filesystem;

const std::array<double, 4> kDriftyOdometry = {0.1, 0.01, 0.1, 0.01};

std::string Installed() {
  std::ifstream in(MrptGraphSlamIniPath());
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path WriteTemp(const std::string& name, const std::string& text) {
  const fs::path p = FreshTempDir("graphslam_ini") / name;
  std::ofstream(p) << text;
  return p;
}

TEST(MrptGraphSlamIni, DefaultsAreTheInstalledFilesValues) {
  // laser_odometry_LC.ini of Debian's mrpt-common 2.5.8 (trailing "// meters" and "1.5;" included).
  const MrptGraphSlamConfig c = ReadMrptGraphSlamIni(MrptGraphSlamIniPath());
  EXPECT_EQ(c.registration_max_distance_m, 0.1);
  EXPECT_EQ(c.registration_max_angle_deg, 15.0);
  EXPECT_EQ(c.icp_prev_nodes, 10);
  EXPECT_EQ(c.lc_min_nodeid_diff, 20);
  EXPECT_EQ(c.lc_min_remote_nodes, 3);
  EXPECT_EQ(c.lc_eigenvalues_ratio_thresh, 2.0);
  EXPECT_EQ(c.partition_threshold, 0.7);
  EXPECT_EQ(c.optimization_distance_m, 1.5);
  EXPECT_EQ(c.optimizer_max_iterations, 100);
  EXPECT_EQ(c.icp_max_iterations, 100);
  EXPECT_EQ(c.icp_threshold_dist_m, 0.3);
  EXPECT_EQ(c.icp_threshold_ang_deg, 5.0);
  EXPECT_EQ(c.icp_alfa, 0.8);
  EXPECT_EQ(c.icp_smallest_threshold_dist_m, 0.05);
  EXPECT_EQ(c.icp_points_decimation, 5);
  EXPECT_TRUE(c.icp_levenberg_marquardt);
  // `slambox algorithms --params mrpt-graphslam` lists them.
  for (const auto& p : MrptGraphSlamModule().params())
    if (p.name == "registration_max_distance_m") EXPECT_EQ(p.default_value, "0.1");
}

TEST(MrptGraphSlamIni, ValuesComeFromTheFileNotFromTheCode) {
  std::string text = Installed();
  const std::string key = "registration_max_distance = 0.1";
  const auto at = text.find(key);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, key.size(), "registration_max_distance = 0.25");
  const fs::path p = WriteTemp("changed.ini", text);
  EXPECT_EQ(ReadMrptGraphSlamIni(p.string()).registration_max_distance_m, 0.25);
  fs::remove_all(p.parent_path());
}

TEST(MrptGraphSlamIni, MissingFileIsAClearError) {
  try {
    ReadMrptGraphSlamIni("/nonexistent/laser_odometry_LC.ini");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("mrpt-common"), std::string::npos) << e.what();
  }
}

TEST(MrptGraphSlamIni, EngineFileCarriesTheModulesValuesAndIsQuiet) {
  MrptGraphSlamConfig c = ReadMrptGraphSlamIni(MrptGraphSlamIniPath());
  c.registration_max_distance_m = 0.35;
  c.icp_prev_nodes = 4;
  c.optimization_distance_m = 2.25;
  c.icp_threshold_dist_m = 0.123;
  c.icp_levenberg_marquardt = false;
  const std::string text = WriteMrptGraphSlamIni(MrptGraphSlamIniPath(), c);
  const fs::path p = WriteTemp("engine.ini", text);
  const MrptGraphSlamConfig back = ReadMrptGraphSlamIni(p.string());
  EXPECT_EQ(back.registration_max_distance_m, 0.35);
  EXPECT_EQ(back.icp_prev_nodes, 4);
  EXPECT_EQ(back.optimization_distance_m, 2.25);
  EXPECT_EQ(back.icp_threshold_dist_m, 0.123);
  EXPECT_FALSE(back.icp_levenberg_marquardt);
  EXPECT_EQ(back.lc_min_nodeid_diff, 20);  // untouched values stay the file's
  EXPECT_NE(text.find("class_verbosity"), std::string::npos);
  EXPECT_EQ(text.find("class_verbosity = 1"), std::string::npos) << "every section set to errors only";
  fs::remove_all(p.parent_path());
}

Estimate RunGraphSlam(const Stream& s, const ParamOverrides& overrides = {}) {
  auto module = MrptGraphSlamModule().create(overrides);
  return Replay(*module, s);
}

// Position RMSE [m] in the 4 m room, seeds 7 and 8; the test prints them:
// ./build/tests/mrpt_graphslam_test --gtest_filter=MrptGraphSlam.Room*
constexpr double kRoomRmse_m[] = {0.0887, 0.0922};

TEST(MrptGraphSlam, RoomPoseAtEveryScanBetterThanDeadReckoning) {
  for (int i = 0; i < 2; ++i) {
    const std::uint64_t seed = 7 + i;
    const Stream s = LidarStream(4.0, seed, kDriftyOdometry);
    const Estimate e = RunGraphSlam(s);
    std::set<double> times;
    for (const auto& p : e.trajectory) {
      ASSERT_TRUE(std::isfinite(p.pose.x) && std::isfinite(p.pose.y) && std::isfinite(p.pose.theta)) << p.t_s;
      times.insert(p.t_s);
    }
    for (size_t k = 1; k < e.trajectory.size(); ++k) ASSERT_GT(e.trajectory[k].t_s, e.trajectory[k - 1].t_s);
    size_t scans = 0, missing = 0;
    for (const auto& ev : s.events)
      if (const auto* scan = std::get_if<LaserScanEvent>(&ev)) ++scans, missing += times.count(scan->t_s) ? 0 : 1;
    EXPECT_EQ(missing, 0u) << "of " << scans << " scans";
    const double rmse = Rmse(PositionErrors(e, s));
    const double dr = DeadReckoningRmse(e, s);
    std::printf("mrpt-graphslam seed %d: %.4f m (dead reckoning %.3f m), %.0f nodes, %.0f loop closures\n",
                static_cast<int>(seed), rmse, dr, e.diagnostics.at("graph_nodes").back().second,
                e.diagnostics.count("edges_LC") ? e.diagnostics.at("edges_LC").back().second : 0.0);
    EXPECT_LT(rmse, 0.75 * dr) << "seed " << seed;  // 0.66 and 0.48 of it
    EXPECT_TRUE(NoWorseThanMeasured(rmse, kRoomRmse_m[i])) << "seed " << seed;
    EXPECT_GT(e.diagnostics.at("graph_nodes").back().second, 20.0);
    EXPECT_GT(e.map_points.size(), 100u);
  }
}

TEST(MrptGraphSlam, DeterministicForAStream) {
  Stream s = LidarStream(4.0, 7, kDriftyOdometry);
  s.events.resize(300);
  ExpectIdenticalTrajectories(RunGraphSlam(s), RunGraphSlam(s));
}

TEST(MrptGraphSlam, ParametersReachTheEngine) {
  // Nodes every 0.1 m by default; every 0.5 m gives several times fewer.
  Stream s = LidarStream(4.0, 7, kDriftyOdometry);
  s.events.resize(400);
  const double fine = RunGraphSlam(s).diagnostics.at("graph_nodes").back().second;
  const double coarse = RunGraphSlam(s, {{"registration_max_distance_m", "0.5"}}).diagnostics.at("graph_nodes").back().second;
  EXPECT_GT(fine, 2.5 * coarse) << fine << " vs " << coarse;
}

TEST(MrptGraphSlam, NamedOnlyNotInAll) {
  // The shipped manifest carries the flag; `all` runs the other MRPT peers, not this one.
  const fs::path bin = fs::path(SLAMBOX_BINARY).parent_path().parent_path();
  const std::string manifest = ReadText(bin / "lib/slambox/plugins/slambox-mrpt.manifest.json");
  const auto at = manifest.find("\"name\": \"mrpt-graphslam\"");
  ASSERT_NE(at, std::string::npos) << manifest;
  const auto module_start = manifest.rfind('{', at);
  EXPECT_NE(manifest.substr(module_start, at - module_start).find("\"in_all\": false"), std::string::npos) << manifest;
  auto r = RunSlambox(SLAMBOX_BINARY, "algorithms");
  ASSERT_EQ(r.code, 0) << r.output;
  const auto line_at = r.output.find("mrpt-graphslam ");
  ASSERT_NE(line_at, std::string::npos) << r.output;
  EXPECT_NE(r.output.substr(line_at, r.output.find('\n', line_at) - line_at).find("(named only, not in all)"),
            std::string::npos);
  const fs::path dir = FreshTempDir("graphslam_all");
  r = RunSlambox(SLAMBOX_BINARY, "run loop --set duration_s=3 --algo all --no-figures -q -o " + (dir / "all").string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::string metrics = ReadText(dir / "all/metrics.json");
  EXPECT_NE(metrics.find("\"mrpt-icp-slam\""), std::string::npos);
  EXPECT_EQ(metrics.find("\"mrpt-graphslam\""), std::string::npos);
  r = RunSlambox(SLAMBOX_BINARY, "run loop --set duration_s=3 --algo all,mrpt-graphslam --no-figures -q -o " +
                                     (dir / "named").string());
  ASSERT_EQ(r.code, 0) << r.output;
  metrics = ReadText(dir / "named/metrics.json");
  EXPECT_NE(metrics.find("\"mrpt-graphslam\""), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace slambox::testing
