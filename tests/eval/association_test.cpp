#include "eval/association.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace slambox {
namespace {

std::vector<StampedPose> Line(const std::vector<double>& t) {
  std::vector<StampedPose> out;
  for (double s : t) out.push_back({s, SE2(s, 0.0, 0.0)});  // x = t identifies the pose
  return out;
}

TEST(Association, ExactStampsMatchExactly) {
  const auto gt = Line({0.0, 0.1, 0.2, 0.3, 0.4});
  const auto est = Line({0.1, 0.3});
  const Association a = Associate(gt, est);
  ASSERT_EQ(a.t_s.size(), 2u);
  EXPECT_EQ(a.groundtruth[0].x, 0.1);
  EXPECT_EQ(a.groundtruth[1].x, 0.3);
  EXPECT_EQ(a.estimate_index[1], 1);
  EXPECT_DOUBLE_EQ(a.distance_m[1], 0.3);
}

TEST(Association, NearestWithinToleranceAsEvo) {
  const auto gt = Line({0.0, 1.0, 2.0, 3.0});
  // 1.004 -> 1.0 (dt 0.004); 2.02 -> no match (dt 0.02 > 0.01); 2.5: tie 2.0/3.0 -> dropped anyway.
  const auto est = Line({1.004, 2.02});
  const Association a = Associate(gt, est);
  ASSERT_EQ(a.t_s.size(), 1u);
  EXPECT_EQ(a.groundtruth[0].x, 1.0);
  EXPECT_EQ(a.estimate[0].x, 1.004);
  const Association wide = Associate(gt, est, {.max_time_diff_s = 0.05});
  EXPECT_EQ(wide.t_s.size(), 2u);
}

TEST(Association, TieTakesFirstStampLikeArgmin) {
  const auto gt = Line({1.0, 2.0, 3.0});
  const auto est = Line({1.5});
  const Association a = Associate(gt, est, {.max_time_diff_s = 1.0});
  ASSERT_EQ(a.t_s.size(), 1u);
  EXPECT_EQ(a.groundtruth[0].x, 1.0);
}

TEST(Association, WalksTheShorterTrajectoryLikeEvo) {
  // The estimate has more poses: evo walks the reference and may match one estimate twice.
  const auto gt = Line({0.0, 0.002});
  const auto est = Line({0.0, 0.001, 0.0015, 5.0});
  const Association a = Associate(gt, est);
  ASSERT_EQ(a.t_s.size(), 2u);
  EXPECT_EQ(a.estimate_index[0], 0);
  EXPECT_EQ(a.estimate_index[1], 2);  // nearest to 0.002 is 0.0015
}

TEST(Association, InterpolatesWithWrappedHeading) {
  std::vector<StampedPose> gt = {{0.0, SE2(0, 0, 170.0 * M_PI / 180)}, {1.0, SE2(2, 4, -170.0 * M_PI / 180)}};
  std::vector<StampedPose> est = {{0.25, SE2()}, {1.0, SE2()}, {1.5, SE2()}};
  const Association a = Associate(gt, est, {.interpolate = true});
  ASSERT_EQ(a.t_s.size(), 2u);  // 1.5 is outside the ground-truth span
  EXPECT_NEAR(a.groundtruth[0].x, 0.5, 1e-12);
  EXPECT_NEAR(a.groundtruth[0].y, 1.0, 1e-12);
  EXPECT_NEAR(a.groundtruth[0].theta, 175.0 * M_PI / 180, 1e-12);  // along the short arc through 180
  EXPECT_NEAR(a.distance_m[0], 0.25 * std::sqrt(20.0), 1e-12);
  EXPECT_EQ(a.groundtruth[1].theta, gt[1].pose.theta);  // exact stamp: unchanged bits
  EXPECT_EQ(a.groundtruth[1].x, 2.0);
}

TEST(Association, CumulativeDistance) {
  const auto d = CumulativeDistance({SE2(0, 0, 0), SE2(3, 4, 1), SE2(3, 4, 2), SE2(3, 5, 0)});
  ASSERT_EQ(d.size(), 4u);
  EXPECT_DOUBLE_EQ(d[1], 5.0);
  EXPECT_DOUBLE_EQ(d[2], 5.0);
  EXPECT_DOUBLE_EQ(d[3], 6.0);
}

}  // namespace
}  // namespace slambox
