// Keyframe decimation of a landmark graph (slam/keyframe_decimation.hpp): the stride, which
// keyframes and observations stay, the composed odometry and its covariance in closed form, and the
// solution spread back onto the dropped keyframes.
#include "slam/keyframe_decimation.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "slam/range_bearing.hpp"

namespace slambox {
namespace {

// n keyframes on a gentle arc (crossing theta = +-pi near the end), two landmarks seen by
// every keyframe, exact measurements; odometry covariance diag(a, b, c) per factor.
LandmarkGraph Arc(int n, const Eigen::Vector3d& variances = {1e-4, 2e-4, 3e-5}) {
  LandmarkGraph g;
  g.observation_covariance = Eigen::Vector2d(1e-4, 1e-6).asDiagonal();
  for (int i = 0; i < n; ++i) {
    g.poses.push_back(SE2(0.8 * i, 0.05 * i * i, 2.9 + 0.07 * i));
    if (i > 0) g.odometry.push_back({i - 1, Between(g.poses[i - 1], g.poses[i]), variances.asDiagonal()});
  }
  g.landmarks = {{7, {3, 4}}, {9, {5, -2}}};
  for (int i = 0; i < n; ++i)
    for (const auto& [key, m] : g.landmarks) g.observations.push_back({i, key, PredictObservation(g.poses[i], m).z});
  return g;
}

TEST(KeyframeDecimation, StrideKeepsAtMostTheCap) {
  EXPECT_EQ(DecimationStride(0, 100), 1);
  EXPECT_EQ(DecimationStride(99, 100), 1);   // 100 keyframes
  EXPECT_EQ(DecimationStride(100, 100), 2);  // 101
  EXPECT_EQ(DecimationStride(299, 100), 3);
  EXPECT_EQ(DecimationStride(5000, 0), 1);   // no cap
}

TEST(KeyframeDecimation, KeepsEveryStrideThKeyframeAndTheLastWithTheirObservations) {
  const LandmarkGraph g = Arc(10);
  const DecimatedGraph d = DecimateKeyframes(g, 4);
  EXPECT_EQ(d.kept, (std::vector<int>{0, 4, 8, 9}));
  ASSERT_EQ(d.graph.poses.size(), 4u);
  ASSERT_EQ(d.graph.odometry.size(), 3u);
  ASSERT_EQ(d.graph.observations.size(), 8u);
  for (size_t i = 0; i < d.kept.size(); ++i) {
    EXPECT_EQ(d.graph.poses[i].vector(), g.poses[static_cast<size_t>(d.kept[i])].vector());
    EXPECT_EQ(d.graph.observations[2 * i].keyframe, static_cast<int>(i));
    EXPECT_EQ(d.graph.observations[2 * i].z, g.observations[2 * static_cast<size_t>(d.kept[i])].z);
  }
  for (size_t i = 0; i < d.graph.odometry.size(); ++i) {
    // The composed odometry is the relative pose of the kept keyframes (exact data), angle wrapped.
    const SE2 expected = Between(d.graph.poses[i], d.graph.poses[i + 1]);
    EXPECT_EQ(d.graph.odometry[i].from, static_cast<int>(i));
    EXPECT_LT((d.graph.odometry[i].T_from_to.translation() - expected.translation()).norm(), 1e-12);
    EXPECT_LT(std::abs(NormalizeAngle(d.graph.odometry[i].T_from_to.theta - expected.theta)), 1e-12);
  }
  EXPECT_EQ(d.graph.landmarks, g.landmarks);
  // Stride 1 is the graph itself.
  const DecimatedGraph same = DecimateKeyframes(g, 1);
  EXPECT_EQ(same.graph.poses.size(), g.poses.size());
  EXPECT_EQ(same.graph.observations.size(), g.observations.size());
  EXPECT_EQ(same.graph.odometry[3].covariance, g.odometry[3].covariance);
}

TEST(KeyframeDecimation, ComposedCovarianceByHand) {
  // Two unit steps along x, each with covariance diag(a, b, c): the composition (2, 0, 0)
  // has var x = 2a, var y = 2b + c (the first step's heading swings the second's 1 m),
  // var theta = 2c, cov(y, theta) = c.
  const double a = 1e-4, b = 2e-4, c = 3e-5;
  LandmarkGraph g;
  g.poses = {SE2(0, 0, 0), SE2(1, 0, 0), SE2(2, 0, 0)};
  for (int i = 0; i < 2; ++i) g.odometry.push_back({i, SE2(1, 0, 0), Eigen::Vector3d(a, b, c).asDiagonal()});
  const DecimatedGraph d = DecimateKeyframes(g, 2);
  ASSERT_EQ(d.graph.odometry.size(), 1u);
  Eigen::Matrix3d expected;
  expected << 2 * a, 0, 0, 0, 2 * b + c, c, 0, c, 2 * c;
  EXPECT_LT((d.graph.odometry[0].covariance - expected).norm(), 1e-15);
  EXPECT_LT((d.graph.odometry[0].T_from_to.vector() - Eigen::Vector3d(2, 0, 0)).norm(), 1e-15);
}

TEST(KeyframeDecimation, SolvedPosesSpreadRigidlyToTheDroppedKeyframes) {
  LandmarkGraph g = Arc(9);
  const LandmarkGraph before = g;
  DecimatedGraph d = DecimateKeyframes(g, 3);  // kept 0, 3, 6, 8
  ASSERT_EQ(d.kept, (std::vector<int>{0, 3, 6, 8}));
  // A "solution" that moves each kept keyframe differently, and one landmark.
  for (size_t i = 1; i < d.graph.poses.size(); ++i)
    d.graph.poses[i] = SE2(0.1 * i, -0.2, 0.3 * i) * d.graph.poses[i];
  d.graph.landmarks[7] = Eigen::Vector2d(3.5, 4.5);
  d.graph.landmarks.erase(9);  // as a solve drops a landmark with no kept observation
  SpreadDecimatedSolution(d, g);
  for (size_t i = 0; i < d.kept.size(); ++i) {
    const auto k = static_cast<size_t>(d.kept[i]);
    EXPECT_EQ(g.poses[k].vector(), d.graph.poses[i].vector());
    const size_t end = i + 1 < d.kept.size() ? static_cast<size_t>(d.kept[i + 1]) : k + 1;
    for (size_t j = k + 1; j < end; ++j) {  // dropped: the same pose relative to its kept keyframe
      const SE2 was = Between(before.poses[k], before.poses[j]), is = Between(g.poses[k], g.poses[j]);
      EXPECT_LT((was.translation() - is.translation()).norm(), 1e-12) << j;
      EXPECT_LT(std::abs(NormalizeAngle(was.theta - is.theta)), 1e-12) << j;
    }
  }
  EXPECT_EQ(g.landmarks.at(7), Eigen::Vector2d(3.5, 4.5));
  EXPECT_EQ(g.landmarks.at(9), before.landmarks.at(9));  // kept its guess
}

TEST(KeyframeDecimation, TheDecimatedGraphSolvesToTheTruthAndSoDoesTheSpreadGraph) {
  // Exact data, guesses off by one rigid motion per kept keyframe and the keyframes dropped
  // after it (none for the first, the gauge): the decimated solve finds the truth at the
  // kept keyframes and the landmarks, and spreading moves the dropped ones onto it too.
  const LandmarkGraph truth = Arc(12);
  LandmarkGraph g = truth;
  for (size_t i = 5; i < g.poses.size(); ++i) {
    const double block = i < 10 ? 1 : static_cast<double>(i) - 8;  // kept 5, 10, 11 start blocks 1, 2, 3
    g.poses[i] = SE2(0.1 * block, -0.2, 0.05 * block) * g.poses[i];
  }
  for (auto& [key, m] : g.landmarks) m += Eigen::Vector2d(0.2, 0.1);
  DecimatedGraph d = DecimateKeyframes(g, 5);  // kept 0, 5, 10, 11
  const LandmarkGraphSolution s = SolveLandmarkGraph(d.graph, {.compute_covariance = false});
  ASSERT_TRUE(s.usable);
  EXPECT_LT(s.chi2_final, 1e-8);
  SpreadDecimatedSolution(d, g);
  for (size_t i = 0; i < g.poses.size(); ++i) {
    EXPECT_LT((g.poses[i].translation() - truth.poses[i].translation()).norm(), 1e-5) << i;
    EXPECT_LT(std::abs(NormalizeAngle(g.poses[i].theta - truth.poses[i].theta)), 1e-6) << i;
  }
  for (const auto& [key, m] : truth.landmarks) EXPECT_LT((g.landmarks.at(key) - m).norm(), 1e-5);
}

TEST(KeyframeDecimation, RejectsABrokenChainAndAZeroStride) {
  LandmarkGraph g = Arc(5);
  EXPECT_THROW(DecimateKeyframes(g, 0), std::invalid_argument);
  g.odometry.pop_back();
  EXPECT_THROW(DecimateKeyframes(g, 2), std::invalid_argument);
  g = Arc(5);
  std::swap(g.odometry[1], g.odometry[2]);
  EXPECT_THROW(DecimateKeyframes(g, 2), std::invalid_argument);
}

}  // namespace
}  // namespace slambox
