// Every metric that subtracts two headings, exercised with *different* trajectories whose
// headings straddle ±pi: the true difference is a few degrees, an unwrapped one is ~358 deg.
// (Identical trajectories cannot catch a dropped NormalizeAngle: their difference is 0 either way.)
#include <gtest/gtest.h>

#include <cmath>

#include "eval/association.hpp"
#include "eval/consistency.hpp"
#include "eval/kitti_segments.hpp"
#include "eval/loop_closures.hpp"
#include "eval/rpe.hpp"

namespace slambox {
namespace {

constexpr double kDeg = M_PI / 180.0;

TEST(AngleWrapEdges, RpeRotationAcrossPiWithDifferentTrajectories) {
  // Ground truth turns +179 deg, the estimate -179 deg (= +181): they differ by 2 deg.
  const std::vector<SE2> gt = {SE2(0, 0, 0), SE2(1, 0, 179 * kDeg)};
  const std::vector<SE2> est = {SE2(0, 0, 0), SE2(1, 0, -179 * kDeg)};
  const RpeResult r = ComputeRpe(gt, est, {.delta = 1, .unit = DeltaUnit::kFrames});
  ASSERT_EQ(r.pairs.size(), 1u);
  EXPECT_NEAR(r.rotation_deg[0], 2.0, 1e-9);
  EXPECT_NEAR(r.translation_m[0], 0.0, 1e-12);
}

TEST(AngleWrapEdges, KittiRotationAcrossPi) {
  // 102 poses 1 m apart: exactly one segment, L = 100 m, from pose 0 to pose 101 (the first
  // whose path exceeds 100 m). The relative headings are +179 and -179 deg: 2 deg / 100 m.
  std::vector<SE2> gt, est;
  for (int i = 0; i <= 101; ++i) {
    gt.emplace_back(i, 0, i == 101 ? 179 * kDeg : 0.0);
    est.emplace_back(i, 0, i == 101 ? -179 * kDeg : 0.0);
  }
  const KittiResult k = KittiSegmentErrors(gt, est);
  ASSERT_EQ(k.segments, 1);
  EXPECT_NEAR(k.rotation_deg_per_m, 2.0 / 100.0, 1e-9);
  EXPECT_NEAR(k.translation_percent, 0.0, 1e-9);
}

TEST(AngleWrapEdges, PoseNeesAcrossPi) {
  // Heading error 2 deg with sigma 1 deg and no position error: NEES = (2/1)^2 = 4.
  Eigen::Matrix3d P = Eigen::Matrix3d::Identity();
  P(2, 2) = kDeg * kDeg;
  EXPECT_NEAR(PoseNees(SE2(3, 4, 179 * kDeg), SE2(3, 4, -179 * kDeg), P), 4.0, 1e-6);
}

TEST(AngleWrapEdges, LoopClosureCorrectnessAcrossPi) {
  // True relative pose +179.5 deg, measured -179.5 deg: 1 deg off, inside the 2 deg test.
  const std::vector<StampedPose> gt = {{0.0, SE2(0, 0, 0)}, {1.0, SE2(0, 0, 179.5 * kDeg)}};
  const std::vector<LoopClosureRecord> closures = {
      {.t_from_s = 0.0, .t_to_s = 1.0, .T_from_to = SE2(0, 0, -179.5 * kDeg), .accepted = true}};
  const LoopClosureResult r = EvaluateLoopClosures(closures, gt);
  ASSERT_EQ(r.accepted, 1);
  EXPECT_EQ(r.accepted_correct, 1);
  EXPECT_DOUBLE_EQ(r.precision, 1.0);
}

TEST(AngleWrapEdges, InterpolationTakesTheShorterArcAcrossPi) {
  // 179 deg -> -179 deg: halfway is +-180 deg, not 0 deg.
  const std::vector<StampedPose> traj = {{0.0, SE2(0, 0, 179 * kDeg)}, {1.0, SE2(2, 0, -179 * kDeg)}};
  SE2 pose;
  int lower = -1;
  double u = 0.0;
  ASSERT_TRUE(InterpolatePose(traj, 0.5, pose, lower, u));
  EXPECT_NEAR(pose.x, 1.0, 1e-12);
  EXPECT_NEAR(std::abs(NormalizeAngle(pose.theta - M_PI)), 0.0, 1e-9);
  ASSERT_TRUE(InterpolatePose(traj, 0.25, pose, lower, u));
  EXPECT_NEAR(std::abs(NormalizeAngle(pose.theta - 179.5 * kDeg)), 0.0, 1e-9);
}

}  // namespace
}  // namespace slambox
