// `slambox run` end to end: the run folder's files and keys (DESIGN.md), determinism of
// the accuracy metrics, and clear errors with a non-zero exit for bad input.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/json_io.hpp"
#include "core/ros_map.hpp"
#include "tests/support/slambox_cli.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kBinary = SLAMBOX_BINARY;

using Result = slambox::testing::CliResult;

Result Slambox(const std::string& args) { return slambox::testing::RunSlambox(kBinary, args); }

json ReadJson(const fs::path& p) {
  std::ifstream in(p);
  return json::parse(in);
}

fs::path TempDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("slambox_run_" + name + "_" + std::to_string(getpid()));
  fs::remove_all(dir);
  return dir;
}

TEST(Run, WritesTheRunFolderOfTheDesign) {
  const fs::path dir = TempDir("loop");
  const Result r = Slambox("run loop --algo odometry --set duration_s=30 --no-figures -o " + dir.string());
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* f : {"metrics.json", "groundtruth.tum", "odometry.tum", "world.json", "estimates/odometry.json",
                        "series/odometry.json"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  const json m = ReadJson(dir / "metrics.json");
  for (const char* k : {"slambox_version", "scenario", "seed", "duration_s", "distance_m", "algorithms"})
    EXPECT_TRUE(m.contains(k)) << k;
  EXPECT_EQ(m["scenario"], "loop");
  EXPECT_NEAR(m["duration_s"].get<double>(), 30.0, 0.05);
  EXPECT_EQ(m["converted_log"], false);  // a simulated stream: its seed is in titles and reports
  const json& odo = m["algorithms"]["odometry"];
  for (const char* k : {"ate_rmse_m", "ate_mean_m", "ate_max_m", "ate_aligned_rmse_m", "rpe_trans_rmse_m",
                        "rpe_rot_rmse_deg", "anees", "landmark_rmse_m", "loop_closures", "loop_closure_precision",
                        "runtime_s", "realtime_factor", "status"})
    EXPECT_TRUE(odo.contains(k)) << k;
  EXPECT_EQ(odo["status"], "ok");
  EXPECT_GT(odo["ate_rmse_m"].get<double>(), 0.0);
  EXPECT_TRUE(odo["anees"].is_number()) << "dead reckoning propagates a covariance";
  // No temporary files are left behind.
  for (const auto& e : fs::recursive_directory_iterator(dir))
    EXPECT_EQ(e.path().string().find(".tmp."), std::string::npos) << e.path();
  fs::remove_all(dir);
}

TEST(Run, WritesRosMapsOfEveryGridAndOfTheTrueWorld) {
  const fs::path dir = TempDir("maps");
  const Result r = Slambox("run loop --algo odometry,icp-poseslam --set duration_s=20 --no-figures -o " + dir.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_FALSE(fs::exists(dir / "maps" / "odometry.yaml")) << "dead reckoning builds no grid";
  const slambox::OccupancyGrid truth = slambox::ReadRosMap((dir / "maps" / "groundtruth.yaml").string());
  EXPECT_EQ(truth.resolution_m, 0.05);
  EXPECT_GT(std::count(truth.cells.begin(), truth.cells.end(), 100), 1000);
  const slambox::OccupancyGrid map = slambox::ReadRosMap((dir / "maps" / "icp-poseslam.yaml").string());
  const slambox::Estimate e = slambox::EstimateFromJson(ReadJson(dir / "estimates" / "icp-poseslam.json"));
  ASSERT_TRUE(e.grid);
  EXPECT_EQ(map.width, e.grid->width);
  EXPECT_EQ(map.height, e.grid->height);
  EXPECT_EQ(map.origin_m, e.grid->origin_m);
  EXPECT_EQ(map.resolution_m, e.grid->resolution_m);
  for (size_t i = 0; i < map.cells.size(); ++i) {  // trinary quantization of the module's grid
    const int c = e.grid->cells[i];
    ASSERT_EQ(map.cells[i], c < 0 ? -1 : c <= 20 ? 0 : c >= 65 ? 100 : -1) << i;
  }
  fs::remove_all(dir);
}

TEST(Run, SameSeedSameAccuracyDifferentSeedDifferent) {
  const fs::path a = TempDir("a"), b = TempDir("b"), c = TempDir("c");
  const std::string common = "run landmarks --algo odometry --set duration_s=20 --no-figures ";
  ASSERT_EQ(Slambox(common + "--seed 3 -o " + a.string()).code, 0);
  ASSERT_EQ(Slambox(common + "--seed 3 -o " + b.string()).code, 0);
  ASSERT_EQ(Slambox(common + "--seed 4 -o " + c.string()).code, 0);
  auto ate = [](const fs::path& d) { return ReadJson(d / "metrics.json")["algorithms"]["odometry"]["ate_rmse_m"].get<double>(); };
  EXPECT_EQ(ate(a), ate(b));
  EXPECT_NE(ate(a), ate(c));
  std::ifstream ta(a / "odometry.tum"), tb(b / "odometry.tum");
  std::stringstream sa, sb;
  sa << ta.rdbuf();
  sb << tb.rdbuf();
  EXPECT_EQ(sa.str(), sb.str());
  for (const auto& d : {a, b, c}) fs::remove_all(d);
}

TEST(Run, StreamFileReplaysLikeTheScenario) {
  const fs::path dir = TempDir("stream");
  fs::create_directories(dir);
  const std::string stream = (dir / "s.stream").string();
  ASSERT_EQ(Slambox("simulate landmarks --seed 5 --set duration_s=15 -o " + stream).code, 0);
  ASSERT_EQ(Slambox("run " + stream + " --algo odometry --no-figures -o " + (dir / "from_stream").string()).code, 0);
  ASSERT_EQ(Slambox("run landmarks --seed 5 --set duration_s=15 --algo odometry --no-figures -o " + (dir / "direct").string()).code, 0);
  auto ate = [](const fs::path& d) { return ReadJson(d / "metrics.json")["algorithms"]["odometry"]["ate_rmse_m"].get<double>(); };
  EXPECT_EQ(ate(dir / "from_stream"), ate(dir / "direct"));
  const Result r = Slambox("run " + stream + " --seed 2 --no-figures -o " + (dir / "x").string());
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("do not apply to a recorded stream"), std::string::npos) << r.output;
  fs::remove_all(dir);
}

TEST(Run, BadInputGivesAClearErrorAndNoResults) {
  const fs::path dir = TempDir("bad");
  struct Case { std::string args, expect; };
  const std::vector<Case> cases = {
      {"run no-such-scenario -o " + dir.string(), "no-such-scenario"},
      {"run loop --algo nonsense -o " + dir.string(), "unknown algorithm 'nonsense'"},
      {"run loop --set robot.lapz=2 -o " + dir.string(), "lapz"},
      {"run loop --set algo.odometry.nope=1 -o " + dir.string(), "has no parameter 'nope'"},
      {"run loop --set algo.odometry.noise_scale=abc -o " + dir.string(), "is not a finite number"},
      {"run loop --set justakey -o " + dir.string(), "expected KEY=VALUE"},
  };
  for (const auto& c : cases) {
    const Result r = Slambox(c.args);
    EXPECT_NE(r.code, 0) << c.args;
    EXPECT_NE(r.output.find(c.expect), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find("fix:"), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_FALSE(fs::exists(dir / "metrics.json")) << c.args;
  }
}

}  // namespace
