#include "eval/kitti_segments.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "eval/relation_metric.hpp"

namespace slambox {
namespace {

TEST(KittiSegments, ScaleErrorOnAStraightLine) {
  // 1 m spacing, 1000 m; the estimate overestimates distance by 1 %.
  std::vector<SE2> gt, est;
  for (int i = 0; i <= 1000; ++i) {
    gt.emplace_back(i, 0.0, 0.0);
    est.emplace_back(1.01 * i, 0.0, 0.0);
  }
  const KittiResult r = KittiSegmentErrors(gt, est);
  // A segment of length L from frame f ends at f + L + 1 (first distance > L); its error is
  // 0.01 (L + 1) / L. Segments exist for f = 0, 10, ... with f + L + 1 <= 1000.
  double sum = 0.0;
  int count = 0;
  for (int L = 100; L <= 800; L += 100)
    for (int f = 0; f + L + 1 <= 1000; f += 10) {
      sum += 0.01 * (L + 1) / L;
      ++count;
    }
  EXPECT_EQ(r.segments, count);
  EXPECT_NEAR(r.translation_percent, 100.0 * sum / count, 1e-9);
  EXPECT_NEAR(r.rotation_deg_per_m, 0.0, 1e-12);
}

TEST(KittiSegments, HeadingDriftAndShortRuns) {
  // A constant heading offset does not change relative rotations: a drift does. Heading
  // drifts by 0.001 rad per metre: every segment [f, f+L+1] has rotation error 0.001 (L+1).
  std::vector<SE2> gt, est;
  for (int i = 0; i <= 300; ++i) {
    gt.emplace_back(i, 0.0, 0.0);
    est.emplace_back(i, 0.0, 0.001 * i);
  }
  const KittiResult r = KittiSegmentErrors(gt, est, {.lengths_m = {100}, .step_frames = 10});
  double sum = 0.0;
  int count = 0;
  for (int f = 0; f + 101 <= 300; f += 10, ++count) sum += 0.001 * 101 / 100.0;
  EXPECT_EQ(r.segments, count);
  EXPECT_NEAR(r.rotation_deg_per_m, 180.0 / M_PI * sum / count, 1e-9);
  const KittiResult short_run = KittiSegmentErrors({gt.begin(), gt.begin() + 50}, {est.begin(), est.begin() + 50});
  EXPECT_EQ(short_run.segments, 0);
  EXPECT_TRUE(std::isnan(short_run.translation_percent));
}

TEST(RelationMetric, HandComputed) {
  const RelationMetric m = ComputeRelationMetric({1.0, 3.0}, {2.0, 4.0});
  EXPECT_EQ(m.relations, 2);
  EXPECT_DOUBLE_EQ(m.trans_mean_m, 2.0);
  EXPECT_DOUBLE_EQ(m.trans_std_m, 1.0);
  EXPECT_DOUBLE_EQ(m.trans_sq_mean_m2, 5.0);  // (1 + 9) / 2
  EXPECT_DOUBLE_EQ(m.trans_sq_std_m2, 4.0);
  EXPECT_DOUBLE_EQ(m.rot_mean_deg, 3.0);
  EXPECT_DOUBLE_EQ(m.rot_sq_mean_deg2, 10.0);  // (4 + 16) / 2
  EXPECT_DOUBLE_EQ(m.rot_sq_std_deg2, 6.0);
}

}  // namespace
}  // namespace slambox
