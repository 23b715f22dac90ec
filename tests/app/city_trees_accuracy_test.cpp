// cityTrees10000 (iSAM's simulated pose-landmark graph, ../shared/data/landmark/) converted
// as `slambox convert graph` does, with its noise-free ground truth, and replayed by the
// landmark modules as `slambox run` scores them. Skips without the public data
// ($SLAMBOX_DATA or ../shared/data). Measured values and commands: README.md, "Pose-landmark
// graphs as streams".
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "app/graph_log.hpp"
#include "app/registry.hpp"
#include "app/run_modules.hpp"
#include "tests/support/public_data.hpp"

namespace slambox {
namespace {

struct Expected {
  const char* module;
  double min_ate_m, max_ate_m;  ///< measured, with a margin a regression would cross
  double max_anees;             ///< likewise (infinity: not checked)
};

TEST(CityTrees, ConvertedGraphReplaysWithGroundTruth) {
  const std::string graph = testing::PublicDataFile(SLAMBOX_SOURCE_DIR, "landmark/cityTrees10000.txt");
  const std::string poses = testing::PublicDataFile(SLAMBOX_SOURCE_DIR, "groundtruth/cityTrees10000_gt_poses.txt");
  const std::string trees = testing::PublicDataFile(SLAMBOX_SOURCE_DIR, "groundtruth/cityTrees10000_gt_landmarks.txt");
  if (graph.empty() || poses.empty() || trees.empty())
    GTEST_SKIP() << "landmark/cityTrees10000.txt or its ground truth not found; set SLAMBOX_DATA";
  const GraphLog g = ReadGraphLog(graph, {.groundtruth = {poses, trees}});
  EXPECT_EQ(g.report.odometry_steps, 9999);
  EXPECT_EQ(g.report.sightings, 4443);
  EXPECT_EQ(g.report.landmarks, 100);
  EXPECT_EQ(g.report.reversed_steps, 0);
  EXPECT_EQ(g.report.off_chain_edges, 0);
  const Stream s = AssembleLandmarkLog(g.log, graph, {.pose_period_s = 1.0, .fov_deg = 360.0});
  ASSERT_EQ(s.groundtruth.size(), 10000u);
  ASSERT_EQ(s.header.world.landmarks.size(), 100u);
  const EvalOptions options = RunEvalOptions(s, "");
  // Measured (this test prints them): ate_rmse_m 51.36 (dead reckoning: deterministic),
  // 1.751, 0.5085; anees 2.159, 4.676, 2.399.
  for (const Expected& x : {Expected{"odometry", 50.8, 51.9, 3.0}, Expected{"ekf-slam", 0.0, 2.5, 7.0},
                            Expected{"graphslam", 0.0, 0.8, 4.0}}) {
    auto module = FindModule(x.module).create({});
    const ModuleRun run = ReplayAndScore(*module, s, options);
    ASSERT_EQ(run.metrics.status, RunStatus::kOk) << x.module << ": " << run.metrics.reason;
    const double ate = run.metrics.ate.rmse;
    std::printf("cityTrees10000 %s: ate_rmse_m %.4g, anees %.4g, landmark_rmse_m %.4g\n", x.module, ate,
                run.metrics.anees, run.metrics.landmark_rmse_m);
    EXPECT_GT(ate, x.min_ate_m) << x.module;
    EXPECT_LT(ate, x.max_ate_m) << x.module;
    EXPECT_LT(run.metrics.anees, x.max_anees) << x.module;
  }
  // FastSLAM 2.0 (50 particles) differs from draw to draw far more than any change of its
  // defaults does: over seed_offset 0..15 its ATE RMSE spans 2.2 to 14.1 m (mean 7.25;
  // without the closure by re-observation 1.7 to 13.6 m, mean 6.88: slam/README_fastslam.md,
  // "cityTrees10000: one draw says little"). One draw against a bound would fail on any
  // change that consumes the generator differently, so the mean of eight draws is checked
  // (measured 7.61, its standard error about 1.3 m) and every draw against divergence
  // (measured at most 14.1 m). Its pose covariance is far smaller than its error (anees
  // 15423 on draw 0): not checked.
  double sum_m = 0.0;
  const int draws = 8;
  for (int k = 0; k < draws; ++k) {
    auto module = FindModule("fastslam2").create({{"seed_offset", std::to_string(k)}});
    const ModuleRun run = ReplayAndScore(*module, s, options);
    ASSERT_EQ(run.metrics.status, RunStatus::kOk) << "fastslam2 draw " << k << ": " << run.metrics.reason;
    std::printf("cityTrees10000 fastslam2 seed_offset %d: ate_rmse_m %.4g, landmark_rmse_m %.4g\n", k,
                run.metrics.ate.rmse, run.metrics.landmark_rmse_m);
    EXPECT_LT(run.metrics.ate.rmse, 25.0) << "draw " << k;
    sum_m += run.metrics.ate.rmse;
  }
  EXPECT_LT(sum_m / draws, 11.0);
}

}  // namespace
}  // namespace slambox
