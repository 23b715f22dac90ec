// `run --format kitti`, `eval` on KITTI and TUM files (the same metrics for the same
// poses), and `eval --save-results` writing evo's archive; clear errors for mixed input.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/kitti_poses.hpp"
#include "core/zip_archive.hpp"
#include "tests/support/slambox_cli.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

slambox::testing::CliResult Slambox(const std::string& args) { return slambox::testing::RunSlambox(SLAMBOX_BINARY, args); }

class TrajectoryFormats : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = fs::temp_directory_path() / ("slambox_formats_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    const auto r = Slambox("run loop --algo odometry --set duration_s=20 --no-figures --format kitti -o " + dir_.string());
    ASSERT_EQ(r.code, 0) << r.output;
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static json EvalJson(const std::string& args) {
    const auto r = Slambox("eval --json " + args);
    EXPECT_EQ(r.code, 0) << r.output;
    return json::parse(r.output.substr(r.output.find('{')));
  }
  static inline fs::path dir_;
};

TEST_F(TrajectoryFormats, RunWritesMatchedKittiPairs) {
  const auto est = slambox::ReadKittiPoses((dir_ / "odometry.kitti").string());
  const auto gt = slambox::ReadKittiPoses((dir_ / "odometry.groundtruth.kitti").string());
  ASSERT_EQ(est.size(), gt.size());
  EXPECT_GT(est.size(), 100u);
  EXPECT_EQ(est.front().pose.x, gt.front().pose.x) << "the estimate starts at the true start pose";
}

TEST_F(TrajectoryFormats, KittiAndTumGiveTheSameMetrics) {
  const json tum = EvalJson("--gt " + (dir_ / "groundtruth.tum").string() + " --est " + (dir_ / "odometry.tum").string());
  const json kitti = EvalJson("--gt " + (dir_ / "odometry.groundtruth.kitti").string() + " --est " +
                              (dir_ / "odometry.kitti").string());
  const json metrics = json::parse(std::ifstream(dir_ / "metrics.json"))["algorithms"]["odometry"];
  EXPECT_EQ(tum["matched_poses"], kitti["matched_poses"]);
  for (const char* k : {"ate_rmse_m", "ate_max_m", "ate_aligned_rmse_m", "rpe_trans_rmse_m", "rpe_rot_rmse_deg"}) {
    EXPECT_NEAR(kitti[k].get<double>(), tum[k].get<double>(), 1e-9) << k;
    EXPECT_NEAR(tum[k].get<double>(), metrics[k].get<double>(), 1e-9) << k;
  }
}

TEST_F(TrajectoryFormats, SaveResultsWritesEvosArchive) {
  const fs::path zip = dir_ / "odometry_ape.zip";
  const json m = EvalJson("--gt " + (dir_ / "groundtruth.tum").string() + " --est " + (dir_ / "odometry.tum").string() +
                          " --save-results " + zip.string());
  std::vector<std::string> names;
  for (const auto& e : slambox::ReadZipStored(zip.string())) {
    names.push_back(e.name);
    if (e.name == "info.json") {
      EXPECT_EQ(json::parse(e.bytes)["ref_name"], "groundtruth");
      EXPECT_EQ(json::parse(e.bytes)["est_name"], "odometry");
    }
    if (e.name == "stats.json") {
      EXPECT_DOUBLE_EQ(json::parse(e.bytes)["rmse"].get<double>(), m["ate_rmse_m"].get<double>());
    }
  }
  EXPECT_EQ(names, (std::vector<std::string>{"info.json", "stats.json", "error_array.npz", "timestamps.npz",
                                             "seconds_from_start.npz", "distances_from_start.npz"}));
}

TEST_F(TrajectoryFormats, MixedOrUnequalInputIsAClearError) {
  auto r = Slambox("eval --gt " + (dir_ / "groundtruth.tum").string() + " --est " + (dir_ / "odometry.kitti").string());
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("cannot be matched to a TUM file"), std::string::npos) << r.output;
  const fs::path short_kitti = dir_ / "short.kitti";
  std::ofstream(short_kitti) << "1 0 0 0 0 1 0 0 0 0 1 0\n";
  r = Slambox("eval --gt " + (dir_ / "odometry.groundtruth.kitti").string() + " --est " + short_kitti.string());
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("the same number of poses"), std::string::npos) << r.output;
  r = Slambox("run loop --algo odometry --format g2o --no-figures -o " + (dir_ / "x").string());
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("unknown trajectory format"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "x" / "metrics.json"));
}

}  // namespace
