// `slambox convert carmen` end to end: a converted log replays through `slambox run`
// (status ok, pose errors null: no ground truth), bad logs exit non-zero naming the line,
// and icp-poseslam maps the public Intel log when it is present.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/support/public_data.hpp"
#include "tests/support/slambox_cli.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kBinary = SLAMBOX_BINARY;

using Result = slambox::testing::CliResult;

Result Slambox(const std::string& args) { return slambox::testing::RunSlambox(kBinary, args); }

fs::path TempDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("slambox_convert_" + name + "_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A robot driving straight down a 4 m wide corridor with a wall ahead, 181-beam scans.
std::string CorridorLog() {
  std::ostringstream s;
  s.precision(9);
  for (int k = 0; k < 30; ++k) {
    const double x = 0.05 * k, ts = 500.0 + 0.1 * k;
    s << "ODOM " << x << " 0 0 0.5 0 0 " << ts << " host 0\n";
    s << "FLASER 181";
    for (int i = 0; i < 181; ++i) {
      const double a = -M_PI / 2 + i * M_PI / 180;
      const double side = std::abs(std::sin(a)) > 1e-9 ? 2.0 / std::abs(std::sin(a)) : 1e9;
      const double ahead = std::cos(a) > 1e-9 ? (10.0 - x) / std::cos(a) : 1e9;
      s << " " << std::min({side, ahead, 81.0});
    }
    s << " " << x << " 0 0 " << x << " 0 0 " << ts + 0.01 << " host 0\n";
  }
  return s.str();
}

TEST(Convert, CarmenLogReplaysThroughRunWithoutGroundTruth) {
  const fs::path dir = TempDir("corridor");
  std::ofstream(dir / "corridor.clf") << CorridorLog();
  const Result c = Slambox("convert carmen " + (dir / "corridor.clf").string() + " -o " + (dir / "c.stream").string());
  ASSERT_EQ(c.code, 0) << c.output;
  EXPECT_NE(c.output.find("30 scans (181 beams over 180.0 deg"), std::string::npos) << c.output;
  const Result r = Slambox("run " + (dir / "c.stream").string() + " --algo odometry,icp-odometry --no-figures -q -o " +
                           (dir / "run").string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(dir / "run" / "metrics.json");
  const json m = json::parse(in);
  for (const char* name : {"odometry", "icp-odometry"}) {
    const json& a = m.at("algorithms").at(name);
    EXPECT_EQ(a.at("status"), "ok") << a.dump();
    EXPECT_TRUE(a.at("ate_rmse_m").is_null());
    EXPECT_TRUE(a.contains("note"));
    EXPECT_GT(a.at("realtime_factor").get<double>(), 0.0);
  }
  EXPECT_TRUE(fs::exists(dir / "run" / "icp-odometry.tum"));
  // A converted log has no map: `all` skips the localization modules, naming one fails clearly.
  const Result all = Slambox("run " + (dir / "c.stream").string() + " --algo all --no-figures -q -o " + (dir / "all").string());
  ASSERT_EQ(all.code, 0) << all.output;
  std::ifstream all_in(dir / "all" / "metrics.json");
  const json algorithms = json::parse(all_in).at("algorithms");
  EXPECT_TRUE(algorithms.contains("icp-poseslam"));
  EXPECT_FALSE(algorithms.contains("mcl"));
  EXPECT_FALSE(algorithms.contains("icp-localization"));
  const Result mcl = Slambox("run " + (dir / "c.stream").string() + " --algo mcl --no-figures -q -o " + (dir / "mcl").string());
  EXPECT_NE(mcl.code, 0);
  EXPECT_NE(mcl.output.find("known map"), std::string::npos) << mcl.output;
  fs::remove_all(dir);
}

TEST(Convert, BadLogExitsNonZeroNamingTheLine) {
  const fs::path dir = TempDir("bad");
  std::ofstream(dir / "bad.clf") << "ODOM 0 0 0 0 0 0 1.0 host 0\nFLASER 3 1.0 2.0 0 0 0 0 0 0 1.5 host 0\n";
  const Result r = Slambox("convert carmen " + (dir / "bad.clf").string() + " -o " + (dir / "x.stream").string());
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("bad.clf:2"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "x.stream"));
  const Result missing = Slambox("convert carmen " + (dir / "none.clf").string() + " -o " + (dir / "x.stream").string());
  EXPECT_NE(missing.code, 0);
  fs::remove_all(dir);
}

TEST(Convert, IcpPoseSlamMapsTheIntelLogWhenPresent) {
  const std::string intel = slambox::testing::PublicDataFile(SLAMBOX_SOURCE_DIR, "rawlogs/intel.clf.bz2");
  if (intel.empty()) GTEST_SKIP() << "public data absent (../shared/data or $SLAMBOX_DATA)";
  const fs::path dir = TempDir("intel");
  ASSERT_EQ(Slambox("convert carmen " + intel + " -o " + (dir / "intel.stream").string()).code, 0);
  const Result r = Slambox("run " + (dir / "intel.stream").string() + " --algo icp-poseslam --no-figures -q -o " +
                           (dir / "run").string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(dir / "run" / "metrics.json");
  const json a = json::parse(in).at("algorithms").at("icp-poseslam");
  EXPECT_EQ(a.at("status"), "ok");
  // 45 minutes around the lab's corridors: many verified closures (318 at the time of writing).
  EXPECT_GT(a.at("loop_closures").get<int>(), 150) << a.dump();
  fs::remove_all(dir);
}

}  // namespace

namespace {

TEST(Convert, EkfSlamMapsVictoriaParkWhenPresent) {
  const std::string vp =
      slambox::testing::PublicDataFile(SLAMBOX_SOURCE_DIR, "landmark/victoria_park/islsjf/VicPark_clean_data.txt");
  if (vp.empty()) GTEST_SKIP() << "public data absent (../shared/data or $SLAMBOX_DATA)";
  const fs::path dir = TempDir("vp");
  ASSERT_EQ(Slambox("convert victoria-park " + vp + " -o " + (dir / "vp.stream").string()).code, 0);
  const Result r = Slambox("run " + (dir / "vp.stream").string() + " --algo ekf-slam --no-figures -q -o " + (dir / "run").string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(dir / "run" / "metrics.json");
  EXPECT_EQ(json::parse(in).at("algorithms").at("ekf-slam").at("status"), "ok");
  std::ifstream est(dir / "run" / "estimates" / "ekf-slam.json");
  const json e = json::parse(est);
  EXPECT_GT(e.at("landmarks").size(), 100u);  // trees mapped with known ids
  fs::remove_all(dir);
}

}  // namespace
