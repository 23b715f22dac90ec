// FastSLAM's place recognition (constellation_merges, slam/fastslam_constellation.cpp) on a
// scripted revisit: twelve trees mapped at the start, a 60 m drive without scans, then the
// same trees seen from a pose 4 m and 1 degree away from where every particle believes it
// is (beyond every association gate: each tree is mapped a second time). The second map's
// shape is the first's: every particle moves onto the true pose and merges the pairs.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

#include "slam/fastslam.hpp"
#include "tests/slam/scripted_revisit.hpp"

namespace slambox {
namespace {

const SE2 kTrueReturn(-4.0, 0.5, 1.0 * M_PI / 180);

using scripted_revisit::kTrees;
using scripted_revisit::Sum;

Stream RevisitStream(const SE2& true_return = kTrueReturn) {
  return scripted_revisit::RevisitStream(true_return, 30, 15);
}

FastSlam2Config Config() {
  FastSlam2Config config;
  config.particles = 20;
  return config;
}

TEST(FastSlamConstellation, ARevisitBeyondTheGatesIsRecognizedByItsShape) {
  FastSlam2 fastslam(Config());
  const Estimate e = Replay(fastslam, RevisitStream());
  EXPECT_EQ(Sum(e, "constellation_merges"), 12.0);
  EXPECT_EQ(e.landmarks.size(), 12u);
  for (const FastSlamParticle& p : fastslam.particles()) {  // every particle moved, not only the best
    EXPECT_NEAR(p.pose.x, kTrueReturn.x, 0.1);
    EXPECT_NEAR(p.pose.y, kTrueReturn.y, 0.1);
    EXPECT_NEAR(p.pose.theta, kTrueReturn.theta, 0.01);
    EXPECT_EQ(p.map.size, 12);
  }
  for (const LandmarkEstimate& m : e.landmarks) {
    double nearest = 1e9;
    for (const Eigen::Vector2d& tree : kTrees) nearest = std::min(nearest, (m.position - tree).norm());
    EXPECT_LT(nearest, 0.1);
  }
  // The return's detections are reported against the old trees' keys: twelve keys in all.
  std::set<int> keys;
  for (const ObservationAssignment& a : e.observation_assignments) keys.insert(a.landmark);
  EXPECT_EQ(keys.size(), 12u);
}

TEST(FastSlamConstellation, WithoutItTheRevisitIsASecondMap) {
  FastSlam2Config config = Config();
  config.constellation_merges = false;
  FastSlam2 fastslam(config);
  const Estimate e = Replay(fastslam, RevisitStream());
  EXPECT_EQ(Sum(e, "constellation_merges"), 0.0);
  EXPECT_EQ(e.landmarks.size(), 24u);
  // Still near where the odometry says (the particles' sampled drift, about a metre), 4 m off.
  EXPECT_GT((e.trajectory.back().pose.translation() - kTrueReturn.translation()).norm(), 3.0);
}

TEST(FastSlamConstellation, ATurnBeyondTheOdometrysHeadingDriftIsNoMatch) {
  // The same shape turned by 20 degrees, where the motion model's heading noise over the
  // drive allows about 1.6 (sigma): the motion is outside the drift's gate, not a hypothesis.
  FastSlam2 fastslam(Config());
  const Estimate e = Replay(fastslam, RevisitStream(SE2(-4.0, 0.5, 20.0 * M_PI / 180)));
  EXPECT_EQ(Sum(e, "constellation_merges"), 0.0);
  // Mapped a second time (a tree or two whose gate the best particle's own sample reached
  // are associated instead): more than 12 landmarks.
  EXPECT_GT(e.landmarks.size(), 18u);
}

}  // namespace
}  // namespace slambox
