#include "eval/loop_closures.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace slambox {
namespace {

// Two laps around a 10 m x 10 m square at 1 m/s, one pose per 0.1 s.
std::vector<StampedPose> TwoLaps() {
  std::vector<StampedPose> gt;
  const Eigen::Vector2d corners[] = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  double t = 0.0;
  for (int lap = 0; lap < 2; ++lap)
    for (int side = 0; side < 4; ++side) {
      const Eigen::Vector2d a = corners[side], b = corners[(side + 1) % 4];
      const double heading = std::atan2(b.y() - a.y(), b.x() - a.x());
      for (int k = 0; k < 100; ++k, t += 0.1) {
        const Eigen::Vector2d p = a + (b - a) * (k / 100.0);
        gt.push_back({t, SE2(p.x(), p.y(), heading)});
      }
    }
  return gt;
}

SE2 PoseAt(const std::vector<StampedPose>& gt, double t) {
  for (const auto& p : gt)
    if (std::abs(p.t_s - t) < 1e-9) return p.pose;
  return SE2();
}

TEST(LoopClosures, PrecisionAgainstTruthWithTolerance) {
  const auto gt = TwoLaps();
  const double t_from = 1.0, t_to = 41.0;  // same place, one lap apart
  const SE2 T_true = Between(PoseAt(gt, t_from), PoseAt(gt, t_to));
  std::vector<LoopClosureRecord> c = {
      {t_from, t_to, T_true, true},                                   // exact: correct
      {t_from, t_to, T_true * SE2(0.15, 0.0, 0.0), true},             // 0.15 m: correct
      {t_from, t_to, T_true * SE2(0.25, 0.0, 0.0), true},             // 0.25 m: wrong
      {t_from, t_to, T_true * SE2(0.0, 0.0, 3.0 * M_PI / 180), true},  // 3 deg: wrong
      {t_from, t_to, T_true, false},                                  // not accepted: ignored
  };
  const LoopClosureResult r = EvaluateLoopClosures(c, gt);
  EXPECT_EQ(r.proposed, 5);
  EXPECT_EQ(r.accepted, 4);
  EXPECT_EQ(r.accepted_correct, 2);
  EXPECT_DOUBLE_EQ(r.precision, 0.5);
  EXPECT_EQ(r.correct, (std::vector<char>{1, 1, 0, 0, 1}));
}

TEST(LoopClosures, RecallAgainstRevisitEpisodes) {
  const auto gt = TwoLaps();
  const auto episodes = RevisitEpisodes(gt);
  // The second lap revisits the first from (after 10 m of travel) the start onwards.
  ASSERT_EQ(episodes.size(), 1u);
  EXPECT_LT(episodes[0].first, 41.0);
  EXPECT_GT(episodes[0].second, 70.0);
  const LoopClosureRecord in_lap_two{1.0, 41.0, Between(PoseAt(gt, 1.0), PoseAt(gt, 41.0)), true};
  EXPECT_DOUBLE_EQ(EvaluateLoopClosures({in_lap_two}, gt).recall, 1.0);
  const LoopClosureRecord wrong{1.0, 41.0, SE2(5, 5, 1), true};
  EXPECT_DOUBLE_EQ(EvaluateLoopClosures({wrong}, gt).recall, 0.0);
  EXPECT_TRUE(std::isnan(EvaluateLoopClosures({}, gt).precision));
  // One lap only: no revisit, recall undefined.
  const std::vector<StampedPose> one(gt.begin(), gt.begin() + 300);
  EXPECT_TRUE(std::isnan(EvaluateLoopClosures({in_lap_two}, one).recall));
}

}  // namespace
}  // namespace slambox
