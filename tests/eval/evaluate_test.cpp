#include "eval/evaluate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "eval/cost.hpp"

namespace slambox {
namespace {

// A 20 m x 10 m loop at 1 m/s sampled at 10 Hz, heading through +-pi on the top side.
GroundTruth Loop() {
  GroundTruth gt;
  const Eigen::Vector2d c[] = {{0, 0}, {20, 0}, {20, 10}, {0, 10}};
  double t = 0.0;
  for (int side = 0; side < 4; ++side) {
    const Eigen::Vector2d a = c[side], b = c[(side + 1) % 4];
    const double len = (b - a).norm(), heading = std::atan2(b.y() - a.y(), b.x() - a.x());
    for (int k = 0; k < static_cast<int>(len * 10); ++k, t += 0.1) {
      const Eigen::Vector2d p = a + (b - a) * (k / (len * 10));
      gt.trajectory.push_back({t, SE2(p.x(), p.y(), heading)});
    }
  }
  gt.world.wall_segments.push_back({{-1, -1}, {21, -1}});
  gt.world.landmarks = {{0, {5, 2}, 0.1}, {1, {15, 8}, 0.1}};
  return gt;
}

Estimate Copy(const GroundTruth& gt) {
  Estimate e;
  for (const auto& p : gt.trajectory) e.trajectory.push_back({p.t_s, p.pose, Eigen::Matrix3d::Zero(), false});
  return e;
}

TEST(Evaluate, IdenticalEstimateScoresExactlyZero) {
  const GroundTruth gt = Loop();
  const Evaluation ev = EvaluateEstimate(gt, Copy(gt));
  const nlohmann::json m = ToJson(ev.metrics);
  EXPECT_EQ(m["status"], "ok");
  EXPECT_EQ(m["matched_poses"], gt.trajectory.size());
  for (const char* k : {"ate_rmse_m", "ate_mean_m", "ate_max_m", "heading_rmse_deg", "rpe_trans_rmse_m",
                        "rpe_rot_rmse_deg", "rpe_rot_max_deg", "relation_trans_mean_m"}) {
    ASSERT_TRUE(m[k].is_number()) << k;
    EXPECT_EQ(m[k].get<double>(), 0.0) << k;
  }
  EXPECT_TRUE(m["kitti_trans_percent"].is_null());  // a 60 m run has no 100 m segment
  EXPECT_NEAR(m["ate_aligned_rmse_m"].get<double>(), 0.0, 1e-12);
  EXPECT_NEAR(m["distance_m"].get<double>(), 59.9, 1e-9);  // the last pose is 0.1 m short of the start
  EXPECT_GT(m["rpe_pairs"].get<int>(), 50);
}

TEST(Evaluate, DesignKeysAndSeriesArePresent) {
  const GroundTruth gt = Loop();
  Estimate est = Copy(gt);
  std::mt19937_64 rng(2);
  std::normal_distribution<double> n(0.0, 0.05);
  for (auto& p : est.trajectory) {
    p.pose = SE2(p.pose.x + n(rng), p.pose.y + n(rng), p.pose.theta + n(rng));
    p.covariance = Eigen::Vector3d(0.0025, 0.0025, 0.0025).asDiagonal();
    p.has_covariance = true;
  }
  est.step_time_s.assign(est.trajectory.size(), 0.001);
  est.finish_time_s = 0.1;
  const Evaluation ev = EvaluateEstimate(gt, est);
  const nlohmann::json m = ToJson(ev.metrics);
  for (const char* k : {"ate_rmse_m", "ate_mean_m", "ate_max_m", "ate_aligned_rmse_m", "rpe_trans_rmse_m",
                        "rpe_rot_rmse_deg", "anees", "landmark_rmse_m", "loop_closures", "loop_closure_precision",
                        "runtime_s", "realtime_factor", "status"})
    EXPECT_TRUE(m.contains(k)) << k;
  EXPECT_TRUE(m["landmark_rmse_m"].is_null());  // no landmark map
  EXPECT_TRUE(m["loop_closures"].is_null());    // no loop closing
  EXPECT_NEAR(m["anees"].get<double>(), 3.0, 0.3);  // true covariance: ANEES ~ 3
  EXPECT_NEAR(m["ate_rmse_m"].get<double>(), 0.05 * std::sqrt(2.0), 0.01);
  EXPECT_LE(m["ate_aligned_rmse_m"].get<double>(), m["ate_rmse_m"].get<double>());
  const double runtime = 0.001 * est.trajectory.size() + 0.1;
  EXPECT_NEAR(m["runtime_s"].get<double>(), runtime, 1e-9);
  EXPECT_NEAR(m["realtime_factor"].get<double>(), gt.trajectory.back().t_s / runtime, 1e-9);
  EXPECT_NEAR(m["step_time_p95_s"].get<double>(), 0.001, 1e-15);

  const nlohmann::json s = ToJson(ev.series);
  const size_t n_steps = gt.trajectory.size();
  for (const char* k : {"t_s", "distance_m", "ate_m", "heading_error_deg", "nees"}) EXPECT_EQ(s[k].size(), n_steps) << k;
  EXPECT_EQ(s["nees_band_95"].size(), 2u);
  EXPECT_EQ(s["rpe"]["trans_m"].size(), s["rpe"]["distance_m"].size());
  EXPECT_EQ(s["rpe"]["rot_deg"].size(), m["rpe_pairs"].get<size_t>());
  EXPECT_TRUE(s["landmarks"].is_array());
}

TEST(Evaluate, AlignModesAndLandmarks) {
  const GroundTruth gt = Loop();
  Estimate est = Copy(gt);
  const SE2 T_est_gt(3.0, -1.0, 0.4);  // the estimate lives in a rotated, shifted frame
  for (auto& p : est.trajectory) p.pose = T_est_gt * p.pose;
  for (const auto& l : gt.world.landmarks) est.landmarks.push_back({l.id, T_est_gt * l.position, Eigen::Matrix2d::Zero(), false});
  EvalOptions o;
  EXPECT_GT(ToJson(EvaluateEstimate(gt, est, o).metrics)["ate_rmse_m"].get<double>(), 1.0);
  o.align = AlignMode::kSE2;
  const nlohmann::json m = ToJson(EvaluateEstimate(gt, est, o).metrics);
  EXPECT_NEAR(m["ate_rmse_m"].get<double>(), 0.0, 1e-9);
  EXPECT_NEAR(m["landmark_rmse_m"].get<double>(), 0.0, 1e-9);
  EXPECT_EQ(m["landmark_matching"], "id");
  EXPECT_EQ(m["landmark_missed"], 0);
  o.align = AlignMode::kOrigin;
  EXPECT_NEAR(ToJson(EvaluateEstimate(gt, est, o).metrics)["ate_rmse_m"].get<double>(), 0.0, 1e-9);

  // A landmark module that kept no landmark (it reported its detections' assignments) missed
  // every true one; a module that reports neither has no landmark map (null).
  Estimate empty = Copy(gt);
  const nlohmann::json none = ToJson(EvaluateEstimate(gt, empty, o).metrics);
  EXPECT_TRUE(none["landmark_missed"].is_null());
  EXPECT_TRUE(none["landmark_matched"].is_null());
  empty.observation_assignments.push_back({0, 0, -1, false});
  const nlohmann::json lost = ToJson(EvaluateEstimate(gt, empty, o).metrics);
  EXPECT_EQ(lost["landmark_missed"], static_cast<int>(gt.world.landmarks.size()));
  EXPECT_EQ(lost["landmark_matched"], 0);
  EXPECT_EQ(lost["landmark_spurious"], 0);
  EXPECT_TRUE(lost["landmark_rmse_m"].is_null());  // no match to average over
  ASSERT_FALSE(gt.world.landmarks.empty());

  // A trajectory from another tool in its own far-away frame: runaway unless aligned.
  Estimate foreign = Copy(gt);
  for (auto& p : foreign.trajectory) p.pose = SE2(500, 300, 2.0) * p.pose;
  EXPECT_EQ(ToJson(EvaluateEstimate(gt, foreign).metrics)["status"], "diverged");
  EXPECT_EQ(ToJson(EvaluateEstimate(gt, foreign, o).metrics)["status"], "ok");
}

TEST(Evaluate, DivergenceIsReportedAsData) {
  const GroundTruth gt = Loop();
  Estimate nan_pose = Copy(gt);
  nan_pose.trajectory[100].pose.x = std::nan("");
  nlohmann::json m = ToJson(EvaluateEstimate(gt, nan_pose).metrics);
  EXPECT_EQ(m["status"], "diverged");
  EXPECT_NE(m["reason"].get<std::string>().find("non-finite pose"), std::string::npos);
  EXPECT_FALSE(m["ate_rmse_m"].is_null());  // the finite poses are still scored

  Estimate exploding = Copy(gt);
  exploding.trajectory[50].has_covariance = true;
  exploding.trajectory[50].covariance = Eigen::Matrix3d::Identity() * 1e7;
  m = ToJson(EvaluateEstimate(gt, exploding).metrics);
  EXPECT_EQ(m["status"], "diverged");
  EXPECT_NE(m["reason"].get<std::string>().find("exploding covariance"), std::string::npos);

  Estimate runaway = Copy(gt);
  for (size_t i = 200; i < runaway.trajectory.size(); ++i) runaway.trajectory[i].pose.x += 10.0 * (i - 199);
  m = ToJson(EvaluateEstimate(gt, runaway).metrics);
  EXPECT_EQ(m["status"], "diverged");
  EXPECT_NE(m["reason"].get<std::string>().find("runaway error"), std::string::npos);

  Estimate drifting = Copy(gt);  // 10 % odometry-like drift is bad, not divergent
  for (size_t i = 0; i < drifting.trajectory.size(); ++i) drifting.trajectory[i].pose.y += 0.01 * i * 0.1;
  EXPECT_EQ(ToJson(EvaluateEstimate(gt, drifting).metrics)["status"], "ok");

  Estimate late;  // nothing matches ground truth in time
  late.trajectory.push_back({1000.0, SE2(), Eigen::Matrix3d::Zero(), false});
  m = ToJson(EvaluateEstimate(gt, late).metrics);
  EXPECT_EQ(m["status"], "failed");
  EXPECT_TRUE(m["ate_rmse_m"].is_null());
}

// A converted log has no ground truth and an empty world: every metric that needs the
// truth is null (loop-closure precision was 0.0 and the grid was scored against nothing).
TEST(Evaluate, MetricsThatNeedGroundTruthAreNullWithoutIt) {
  const GroundTruth truth = Loop();
  Estimate est = Copy(truth);
  est.loop_closures.push_back({10.0, 50.0, Between(truth.trajectory[100].pose, truth.trajectory[500].pose), true});
  est.landmarks.push_back({0, {5, 2}, Eigen::Matrix2d::Identity() * 0.01, true});
  OccupancyGrid grid;
  grid.width = grid.height = 10;
  grid.resolution_m = 0.5;
  grid.cells.assign(100, 0);
  grid.cells[0] = 100;
  est.grid = grid;
  for (auto& p : est.trajectory) p.has_covariance = true, p.covariance = Eigen::Matrix3d::Identity() * 0.01;
  // With the truth these are numbers (so the test below can fail)...
  const auto with = ToJson(EvaluateEstimate(truth, est).metrics);
  for (const char* key : {"loop_closure_precision", "grid_cell_error", "landmark_rmse_m",
                          "landmark_spurious", "anees", "ate_rmse_m", "rpe_trans_rmse_m", "revisit_episodes", "distance_m"})
    EXPECT_TRUE(with.at(key).is_number()) << key << " " << with.at(key);
  // ...without it they are null, and the counts that need no truth stay.
  const auto m = ToJson(EvaluateEstimate(GroundTruth{}, est).metrics);
  for (const char* key : {"loop_closure_precision", "loop_closure_recall", "revisit_episodes", "grid_cell_error",
                          "grid_known_cells", "grid_mean_nearest_occupied_m", "grid_mean_truth_to_estimate_m",
                          "landmark_rmse_m", "landmark_ospa_m", "landmark_spurious", "landmark_missed",
                          "landmark_anees", "anees", "ate_rmse_m", "ate_aligned_rmse_m", "heading_rmse_deg",
                          "rpe_trans_rmse_m", "rpe_rot_rmse_deg", "kitti_trans_percent", "relation_trans_mean_m",
                          "relation_unmatched", "nees_in_band_fraction", "distance_m"})
    EXPECT_TRUE(m.at(key).is_null()) << key << " " << m.at(key);
  EXPECT_EQ(m.at("alignment_reason"), "the stream has no ground truth");
  EXPECT_EQ(m.at("loop_closures"), 1);
  EXPECT_EQ(m.at("loop_closures_proposed"), 1);
  EXPECT_EQ(m.at("status"), "ok");
}

TEST(Evaluate, AssociationAgreementNeedsTrueIdsAndAssignments) {
  GroundTruth truth = Loop();
  Estimate est = Copy(truth);
  // Two scans: trees 0 and 1, then tree 0 again; the module keeps them apart except the
  // last one, which it makes a new landmark (a duplicate).
  est.observation_assignments = {{0, 0, 5, true}, {0, 1, 6, true}, {1, 0, 7, true}};
  const auto none = ToJson(EvaluateEstimate(truth, est).metrics);  // no observation ids: null
  for (const char* key : {"association_agreement", "association_duplicates", "association_misses",
                          "association_unused"})
    EXPECT_TRUE(none.at(key).is_null()) << key;
  truth.observation_ids = {{0, 1}, {0}};
  const auto m = ToJson(EvaluateEstimate(truth, est).metrics);
  EXPECT_DOUBLE_EQ(m.at("association_agreement").get<double>(), 2.0 / 3.0);
  EXPECT_EQ(m.at("association_duplicates"), 1);
  EXPECT_EQ(m.at("association_misses"), 0);
  EXPECT_EQ(m.at("association_unused"), 0);
  // A real log (no trajectory) is scored too: the ids are its truth.
  const auto log = ToJson(EvaluateEstimate(GroundTruth{{}, {}, truth.observation_ids}, est).metrics);
  EXPECT_DOUBLE_EQ(log.at("association_agreement").get<double>(), 2.0 / 3.0);
}

TEST(Cost, HandComputed) {
  const CostResult c = ComputeCost({0.1, 0.3, 0.2, 0.4}, 1.0, 20.0);
  EXPECT_TRUE(c.available);
  EXPECT_DOUBLE_EQ(c.step_median_s, 0.25);
  EXPECT_NEAR(c.step_p95_s, 0.385, 1e-12);  // numpy: 0.3 + 0.85 * 0.1
  EXPECT_DOUBLE_EQ(c.step_max_s, 0.4);
  EXPECT_NEAR(c.runtime_s, 2.0, 1e-12);
  EXPECT_NEAR(c.realtime_factor, 10.0, 1e-12);
  EXPECT_FALSE(ComputeCost({}, 0.0, 5.0).available);
}

TEST(PathLength, HandComputed) {
  EXPECT_DOUBLE_EQ(PathLength({{0, SE2(0, 0, 0)}, {1, SE2(3, 4, 0)}, {2, SE2(3, 0, 1)}}), 9.0);
  EXPECT_EQ(PathLength({}), 0.0);
}

}  // namespace
}  // namespace slambox
