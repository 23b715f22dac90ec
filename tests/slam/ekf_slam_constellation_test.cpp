// EKF-SLAM's place recognition (constellation_merges, slam/ekf_slam_constellation.cpp) on a
// scripted revisit: twelve trees mapped at the start, a 60 m drive without scans, then the
// same trees seen from a pose 4 m and 3 degrees away from where the filter believes it is
// (beyond every gate: each tree is mapped a second time). The second map's shape is the
// first's: the pairs are merged, the robot lands on its true pose and the map has twelve trees.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include "slam/ekf_slam.hpp"

namespace slambox {
namespace {

const std::vector<Eigen::Vector2d> kTrees = {{3, 1},  {6, -2},  {-4, 3}, {-2, -6}, {7, 4},  {-6, -1},
                                            {1, 7},  {4, -7},  {-8, 6}, {9, -1},  {-3, -9}, {-9, -5}};
const SE2 kTrueReturn(-4.0, 0.5, 3.0 * M_PI / 180);

std::vector<LandmarkObservation> SeenFrom(const SE2& pose) {
  std::vector<LandmarkObservation> z;
  for (const Eigen::Vector2d& m : kTrees) {
    const Eigen::Vector2d local = pose.inverse() * m;
    z.push_back({local.norm(), std::atan2(local.y(), local.x()), -1});
  }
  return z;
}

/// Noise-free detections; the odometry says the robot drove 30 m out and back to the start
/// (small alpha: the filter is sure of its pose to decimetres), the truth ends at kTrueReturn.
Stream RevisitStream(const SE2& true_return = kTrueReturn) {
  Stream s;
  s.header.sensors.odometry = OdometryConfig{.rate_hz = 50, .alpha = {1e-5, 1e-5, 1e-4, 1e-5}};
  s.header.sensors.landmarks = LandmarkSensorConfig{.rate_hz = 5, .range_max_m = 20, .fov_deg = 360,
                                                    .sigma_range_m = 0.05, .sigma_bearing_deg = 0.5,
                                                    .known_ids = false, .clutter_per_scan = 0.0};
  double t = 0.0;
  for (int k = 0; k < 3; ++k) s.events.push_back(LandmarkEvent{t += 0.2, SeenFrom(SE2())});
  for (int leg = 0; leg < 2; ++leg) {
    for (int k = 0; k < 60; ++k) s.events.push_back(OdometryEvent{t += 0.1, SE2(0.5, 0, 0)});
    s.events.push_back(OdometryEvent{t += 0.1, SE2(0, 0, M_PI - 1e-9)});
  }
  for (int k = 0; k < 4; ++k) {
    s.events.push_back(OdometryEvent{t += 0.1, SE2(0, 0, 0)});
    s.events.push_back(LandmarkEvent{t, SeenFrom(true_return)});
  }
  return s;
}

double Sum(const Estimate& e, const std::string& name) {
  const auto it = e.diagnostics.find(name);
  if (it == e.diagnostics.end()) return 0.0;
  return std::accumulate(it->second.begin(), it->second.end(), 0.0,
                         [](double a, const auto& sample) { return a + sample.second; });
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

}  // namespace
}  // namespace slambox
