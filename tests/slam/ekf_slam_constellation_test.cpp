// EKF-SLAM's place recognition (constellation_merges, slam/ekf_slam_constellation.cpp) on a
// scripted revisit: twelve trees mapped at the start, a 60 m drive without scans, then the
// same trees seen from a pose 4 m and 3 degrees away from where the filter believes it is
// (beyond every gate: each tree is mapped a second time). The second map's shape is the
// first's: the pairs are merged, the robot lands on its true pose and the map has twelve trees.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "slam/ekf_slam.hpp"
#include "tests/slam/scripted_revisit.hpp"

namespace slambox {
namespace {

const SE2 kTrueReturn(-4.0, 0.5, 3.0 * M_PI / 180);

using scripted_revisit::kTrees;
using scripted_revisit::Sum;

Stream RevisitStream(const SE2& true_return = kTrueReturn) {
  return scripted_revisit::RevisitStream(true_return, 3, 4);
}

/// Heading recovery off: it would search the revisit under a wider heading prior first.
EkfSlamConfig Config() {
  EkfSlamConfig config;
  config.recover_heading = false;
  return config;
}

TEST(EkfSlamConstellation, ARevisitBeyondTheGatesIsRecognizedByItsShape) {
  EkfSlam ekf(Config());
  const Estimate e = Replay(ekf, RevisitStream());
  EXPECT_EQ(Sum(e, "constellation_merges"), 12.0);
  EXPECT_EQ(e.landmarks.size(), 12u);
  const SE2 end = e.trajectory.back().pose;
  EXPECT_NEAR(end.x, kTrueReturn.x, 0.1);
  EXPECT_NEAR(end.y, kTrueReturn.y, 0.1);
  EXPECT_NEAR(end.theta, kTrueReturn.theta, 0.01);
  for (const LandmarkEstimate& m : e.landmarks) {
    double nearest = 1e9;
    for (const Eigen::Vector2d& tree : kTrees) nearest = std::min(nearest, (m.position - tree).norm());
    EXPECT_LT(nearest, 0.1);
  }
}

TEST(EkfSlamConstellation, WithoutItTheRevisitIsASecondMap) {
  EkfSlamConfig config = Config();
  config.constellation_merges = false;
  EkfSlam ekf(config);
  const Estimate e = Replay(ekf, RevisitStream());
  EXPECT_EQ(Sum(e, "constellation_merges"), 0.0);
  EXPECT_EQ(e.landmarks.size(), 24u);
  EXPECT_LT(e.trajectory.back().pose.translation().norm(), 0.1);  // still where the odometry says, 4 m off
}

TEST(EkfSlamConstellation, ATurnBeyondTheOdometrysHeadingDriftIsNoMatch) {
  // The same shape turned by 20 degrees, where the motion model's heading noise over the
  // drive allows about 1.6 (sigma): the motion is outside the drift's gate, not a hypothesis.
  EkfSlam ekf(Config());
  const Estimate e = Replay(ekf, RevisitStream(SE2(-4.0, 0.5, 20.0 * M_PI / 180)));
  EXPECT_EQ(Sum(e, "constellation_merges"), 0.0);
}

/// Mean distance from each of `trees` to the nearest estimated landmark.
double MeanError(const Estimate& e, const std::vector<Eigen::Vector2d>& trees) {
  double sum = 0.0;
  for (const Eigen::Vector2d& tree : trees) {
    double nearest = 1e9;
    for (const LandmarkEstimate& m : e.landmarks) nearest = std::min(nearest, (m.position - tree).norm());
    sum += nearest;
  }
  return sum / static_cast<double>(trees.size());
}

TEST(EkfSlamConstellation, LandmarksMappedDuringTheDriftTakeTheirShareOfTheCorrection) {
  // The turn at the far end is 4.25 degrees more than the odometry says (3 would leave the
  // return inside the gates, 5 outside the heading prior); the far trees, mapped
  // 10 m after it, are as far off as the return (the window). Moving only the window leaves
  // them where the drift put them; their share of the motion (dead reckoning's heading
  // variance until their sighting over that until now) brings them most of the way.
  SE2 truth;
  const Stream stream = scripted_revisit::DriftStream(SE2(0, 0, 4.25 * M_PI / 180), 3, &truth);
  double error[2];
  for (const bool spread : {false, true}) {
    EkfSlamConfig config = Config();
    config.constellation_spread = spread;
    EkfSlam ekf(config);
    const Estimate e = Replay(ekf, stream);
    EXPECT_GE(Sum(e, "constellation_merges"), 10.0);  // two trees' gates held their returns
    EXPECT_EQ(e.landmarks.size(), 18u);
    EXPECT_LT((e.trajectory.back().pose.translation() - truth.translation()).norm(), 0.1);
    EXPECT_LT(MeanError(e, kTrees), 0.1);
    error[spread] = MeanError(e, scripted_revisit::kFarTrees);
  }
  std::printf("far trees' mean error: %.3f m moving the window only, %.3f m with the shares\n", error[0], error[1]);
  EXPECT_GT(error[0], 0.3);
  EXPECT_LT(error[1], 0.5 * error[0]);
}

}  // namespace
}  // namespace slambox
