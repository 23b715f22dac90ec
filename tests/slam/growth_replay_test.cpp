// The replay of the graph's growth (slam/growth_replay.hpp): exact data solved from front-end
// poses that drift and jump, the schedule past the cap, landmarks placed by their first
// observation, and bad input.
#include "slam/growth_replay.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <utility>

#include "slam/keyframe_decimation.hpp"
#include "slam/range_bearing.hpp"

namespace slambox {
namespace {

struct Loop {
  LandmarkGraph graph;            // exact odometry and observations; poses, landmarks: the truth
  std::vector<SE2> frontend;      // a filter's poses: drifting in heading, then jumping back
};

// n keyframes around a circle of radius 10 m (one lap, crossing theta = +-pi), landmarks on a
// ring of 14 m seen within 8 m.
Loop MakeLoop(int n) {
  Loop l;
  LandmarkGraph& g = l.graph;
  g.observation_covariance = Eigen::Vector2d(1e-4, 1e-6).asDiagonal();
  for (int k = 0; k < n; ++k) {
    const double a = 2 * M_PI * k / n;
    g.poses.push_back(SE2(10 * std::cos(a), 10 * std::sin(a), NormalizeAngle(a + M_PI / 2)));
    if (k > 0) g.odometry.push_back({k - 1, Between(g.poses[k - 1], g.poses[k]), Eigen::Vector3d(1e-4, 1e-4, 1e-5).asDiagonal()});
  }
  for (int j = 0; j < 12; ++j) g.landmarks[100 + j] = 14.0 * Eigen::Vector2d(std::cos(j * M_PI / 6), std::sin(j * M_PI / 6));
  for (int k = 0; k < n; ++k)
    for (const auto& [key, m] : g.landmarks)
      if ((m - g.poses[k].translation()).norm() < 8.0) g.observations.push_back({k, key, PredictObservation(g.poses[k], m).z});
  for (int k = 0; k < n; ++k) {
    const double drift = k < 2 * n / 3 ? 0.01 * k : 0.0;  // 0.01 rad per keyframe, closed at 2/3 of the lap
    l.frontend.push_back(SE2(g.poses[k].x + 0.3 * drift, g.poses[k].y, g.poses[k].theta + drift));
  }
  return l;
}

TEST(GrowthReplay, ExactDataIsSolvedFromDriftingAndJumpingFrontEndPoses) {
  const Loop l = MakeLoop(41);  // solves at 5, 10, ..., 40: every keyframe is solved
  LandmarkGraph full = l.graph;
  for (auto& [key, m] : full.landmarks) m = Eigen::Vector2d(1e3, 1e3);  // positions are not used
  const LandmarkGraph g = ReplayGrowth(full, l.frontend, {.solve_every_keyframes = 5, .max_keyframes = 0, .solver = {}});
  ASSERT_EQ(g.poses.size(), l.graph.poses.size());
  for (size_t k = 0; k < g.poses.size(); ++k) {
    EXPECT_LT((g.poses[k].translation() - l.graph.poses[k].translation()).norm(), 1e-5) << k;
    EXPECT_LT(std::abs(NormalizeAngle(g.poses[k].theta - l.graph.poses[k].theta)), 1e-6) << k;
  }
  ASSERT_EQ(g.landmarks.size(), l.graph.landmarks.size());
  for (const auto& [key, m] : l.graph.landmarks) EXPECT_LT((g.landmarks.at(key) - m).norm(), 1e-5) << key;
}

TEST(GrowthReplay, PastTheCapTheSolvedKeyframesAreExactAndTheLaterOnesFollowTheFrontEnd) {
  // K 3, cap 8: a solve every 3 x stride keyframes, stride = ceil(keyframes / 8): at 3, 6,
  // 12 (stride 2), 21 (3), 36 (5); the last of 0..39 composed after it.
  const Loop l = MakeLoop(40);
  const LandmarkGraph g = ReplayGrowth(l.graph, l.frontend, {.solve_every_keyframes = 3, .max_keyframes = 8, .solver = {}});
  const int last = 36, stride = 5;
  ASSERT_EQ(DecimationStride(last, 8), stride);
  for (int k = 0; k <= last; k += stride) {  // the last solve's kept keyframes
    EXPECT_LT((g.poses[k].translation() - l.graph.poses[k].translation()).norm(), 1e-5) << k;
    EXPECT_LT(std::abs(NormalizeAngle(g.poses[k].theta - l.graph.poses[k].theta)), 1e-6) << k;
  }
  for (int k = last + 1; k < 40; ++k) {  // after it: composed with the front end's motion
    const SE2 expected = g.poses[k - 1] * (l.frontend[k - 1].inverse() * l.frontend[k]);
    EXPECT_LT((g.poses[k].vector() - expected.vector()).norm(), 1e-12) << k;
  }
  // A landmark first seen after the last solve sits at its first observation.
  for (const RangeBearingConstraint& o : l.graph.observations) {
    bool seen_before = false;
    for (const RangeBearingConstraint& p : l.graph.observations) seen_before |= p.landmark == o.landmark && p.keyframe <= last;
    if (seen_before) continue;
    EXPECT_LT((g.landmarks.at(o.landmark) - InverseObservation(g.poses[o.keyframe], o.z).landmark).norm(), 1e-12);
    break;
  }
}

TEST(ComposedMotion, TheFrontEndsMotionUnlessItIsAJumpAwayFromTheOdometry) {
  const SE2 solved(1.0, 2.0, 0.3), fe_prev(5.0, -1.0, 2.0);
  const OdometryConstraint odo{0, SE2(0.5, 0.02, 0.05), Eigen::Vector3d(1e-4, 1e-4, 1e-4).asDiagonal()};  // sigma 1 cm, 0.01 rad
  const double gate = 11.34;  // chi2_3(0.99)
  auto composed = [&](const SE2& motion, double g) { return ComposedMotion(solved, fe_prev, fe_prev * motion, odo, g); };
  auto near = [](const SE2& a, const SE2& b) {
    return (a.translation() - b.translation()).norm() < 1e-12 && std::abs(NormalizeAngle(a.theta - b.theta)) < 1e-12;
  };
  // 2 sigma off in x and in heading: squared distance 8, within the gate: the front end's motion.
  const SE2 corrected(0.52, 0.02, 0.07);
  EXPECT_TRUE(near(composed(corrected, gate), solved * corrected));
  // 3 sigma in x and 2 in heading: 13 > 11.34, a jump: the odometry's motion.
  const SE2 jumped(0.53, 0.02, 0.07);
  EXPECT_TRUE(near(composed(jumped, gate), solved * odo.T_from_to));
  EXPECT_TRUE(near(composed(jumped, 0.0), solved * jumped));  // gate 0: never
  // The heading difference is wrapped: odometry at +pi - 0.005, the front end at -pi + 0.005 (1 sigma apart).
  OdometryConstraint turning = odo;
  turning.T_from_to = SE2(0.5, 0.02, M_PI - 0.005);
  const SE2 wrapped(0.5, 0.02, -M_PI + 0.005);
  EXPECT_TRUE(near(ComposedMotion(solved, fe_prev, fe_prev * wrapped, turning, gate), solved * wrapped));
  // At rest (zero covariance) the floored covariance still weighs: a 1 mm correction is a jump.
  const OdometryConstraint rest{0, SE2(), Eigen::Matrix3d::Zero()};
  EXPECT_TRUE(near(ComposedMotion(solved, fe_prev, fe_prev * SE2(0.001, 0.0, 0.0), rest, gate), solved));
}

TEST(GrowthReplay, AJumpOfTheFrontEndIsNotComposed) {
  // K 20 on 40 keyframes: one solve at 20, keyframes 21..39 composed after it; the front end
  // jumps back by 0.25 rad (and 7.5 cm) between keyframes 25 and 26.
  const Loop l = MakeLoop(40);
  GrowthReplaySettings settings{.solve_every_keyframes = 20, .max_keyframes = 0, .solver = {}};
  const LandmarkGraph plain = ReplayGrowth(l.graph, l.frontend, settings);
  settings.jump_gate_chi2 = 11.34;
  const LandmarkGraph gated = ReplayGrowth(l.graph, l.frontend, settings);
  const SE2 jump = plain.poses[25] * (l.frontend[25].inverse() * l.frontend[26]);
  EXPECT_LT((plain.poses[26].vector() - jump.vector()).norm(), 1e-12);
  const SE2 odometry = gated.poses[25] * l.graph.odometry[25].T_from_to;
  EXPECT_LT((gated.poses[26].vector() - odometry.vector()).norm(), 1e-12);
  // After the jump the front end moves exactly: the gated replay ends at the truth's heading
  // to within the drift it composed before the jump; the plain one 0.25 rad off that.
  EXPECT_NEAR(NormalizeAngle(plain.poses[39].theta - gated.poses[39].theta), -0.25, 0.06);
}

TEST(GrowthReplay, RejectsMismatchedFrontEndPosesAndAZeroInterval) {
  const Loop l = MakeLoop(12);
  std::vector<SE2> short_frontend(l.frontend.begin(), l.frontend.end() - 1);
  EXPECT_THROW(ReplayGrowth(l.graph, short_frontend, {}), std::invalid_argument);
  LandmarkGraph no_odometry = l.graph;
  no_odometry.odometry.pop_back();
  EXPECT_THROW(ReplayGrowth(no_odometry, l.frontend, {}), std::invalid_argument);
  LandmarkGraph out_of_order = l.graph;
  std::swap(out_of_order.odometry[3], out_of_order.odometry[4]);
  EXPECT_THROW(ReplayGrowth(out_of_order, l.frontend, {}), std::invalid_argument);
  EXPECT_THROW(ReplayGrowth(l.graph, l.frontend, {.solve_every_keyframes = 0, .max_keyframes = 0, .solver = {}}), std::invalid_argument);
  EXPECT_TRUE(ReplayGrowth(LandmarkGraph{}, {}, {}).poses.empty());
}

}  // namespace
}  // namespace slambox
