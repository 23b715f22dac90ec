// The smoother's second look at detections the front end left out
// (slam/leftover_association.hpp) and the dead-reckoned gate it uses
// (slam/reobservation_split.hpp, DeadReckoned).
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>

#include "core/se2.hpp"
#include "slam/leftover_association.hpp"
#include "slam/range_bearing.hpp"
#include "slam/reobservation_split.hpp"

namespace slambox {
namespace {

// The landmark seen from k1 carried into k's frame, as a function of the odometry T between
// them (k1 < k: T is k in k1's frame; k1 > k: k1 in k's frame).
Eigen::Vector2d Carried(const SE2& T, const Eigen::Vector2d& p1, bool forward) {
  return forward ? Eigen::Vector2d(T.rotation().transpose() * (p1 - T.translation())) : Eigen::Vector2d(T * p1);
}

TEST(DeadReckoned, CovarianceIsTheOdometrysPropagatedBothWays) {
  // One odometry step, a full covariance, no observation noise: C = J Sigma J^T with J the
  // Jacobian of the carried point in T's (x, y, theta), checked against central differences;
  // exact poses and detection: the difference is zero. Heading near pi: the wrap.
  for (const double theta : {0.4, M_PI - 0.01, -M_PI + 0.02}) {
    const SE2 T(0.8, 0.3, theta);
    LandmarkGraph g;
    g.poses = {SE2(1.0, -2.0, 0.3), SE2(1.0, -2.0, 0.3) * T};
    Eigen::Matrix3d A;
    A << 0.2, 0.05, 0.01, 0.0, 0.3, -0.02, 0.03, 0.0, 0.1;
    const Eigen::Matrix3d Sigma = A * A.transpose();
    g.odometry.push_back({0, T, Sigma});
    g.observation_covariance.setZero();
    const Eigen::Vector2d m(4.0, 1.5);
    for (const bool forward : {true, false}) {
      SCOPED_TRACE(testing::Message() << "theta " << theta << (forward ? " k1 < k" : " k1 > k"));
      const int k1 = forward ? 0 : 1, k = forward ? 1 : 0;
      const Eigen::Vector2d z = PredictObservation(g.poses[k], m).z;
      const DeadReckonedDifference d = DeadReckoned(g, k1, k, m, z);
      EXPECT_LT(d.difference.norm(), 1e-12);
      const Eigen::Vector2d p1 = g.poses[k1].inverse() * m;
      Eigen::Matrix<double, 2, 3> J;
      const double h = 1e-6;
      for (int i = 0; i < 3; ++i) {
        Eigen::Vector3d e = Eigen::Vector3d::Zero();
        e(i) = h;
        const SE2 plus(T.x + e(0), T.y + e(1), T.theta + e(2)), minus(T.x - e(0), T.y - e(1), T.theta - e(2));
        J.col(i) = (Carried(plus, p1, forward) - Carried(minus, p1, forward)) / (2 * h);
      }
      EXPECT_LT((d.C - J * Sigma * J.transpose()).norm(), 1e-7);
    }
  }
}

// Keyframes along x, 1 m apart, precise odometry; landmarks A (3, 2) and B (3, -2) seen
// from keyframes 0..3, a close pair C / D (15, +-0.3) seen from 0 and 1. The solution's
// marginals are small and diagonal.
struct Park {
  Park() {
    for (int k = 0; k < 8; ++k) g.poses.emplace_back(k, 0.0, 0.0);
    for (int k = 0; k + 1 < 8; ++k) g.odometry.push_back({k, SE2(1, 0, 0), Eigen::Vector3d(1e-4, 1e-4, 1e-5).asDiagonal()});
    g.observation_covariance = Eigen::Vector2d(0.01, std::pow(M_PI / 180, 2)).asDiagonal();
    g.landmarks = {{0, {3, 2}}, {1, {3, -2}}, {2, {15, 0.3}}, {3, {15, -0.3}}};
    for (int k = 0; k < 4; ++k)
      for (int key : {0, 1}) g.observations.push_back({k, key, Z(k, key)});
    for (int k = 0; k < 2; ++k)
      for (int key : {2, 3}) g.observations.push_back({k, key, Z(k, key)});
    s.covariance_ok = true;
    s.pose_covariances.assign(8, Eigen::Vector3d(1e-3, 1e-3, 1e-4).asDiagonal());
    for (const auto& [key, m] : g.landmarks) s.landmark_covariances[key] = 1e-3 * Eigen::Matrix2d::Identity();
  }
  Eigen::Vector2d Z(int k, int key, double dy = 0.0) const {
    return PredictObservation(g.poses[k], g.landmarks.at(key) + Eigen::Vector2d(0, dy)).z;
  }
  LandmarkGraph g;
  LandmarkGraphSolution s;
};

TEST(AssociateLeftovers, JoinsTheOneLandmarkInTheGateAndNothingElse) {
  const Park p;
  const LeftoverSettings settings{9.21, 0.01, 1e-4};
  const std::vector<LeftoverDetection> detections = {
      {5, p.Z(5, 0, 0.05)},  // A, 5 cm off: joins A
      {3, p.Z(3, 0)},        // A at a keyframe that observes A already: no
      {5, {4.0, 1.0}},       // nothing there: no
      {6, p.Z(6, 1)},        // B, twice in one scan: neither
      {6, p.Z(6, 1, 0.05)},
      {7, p.Z(7, 2, -0.3)},  // between C and D, both in its gate: no
  };
  EXPECT_EQ(AssociateLeftovers(p.g, p.s, detections, settings), (std::vector<int>{0, -1, -1, -1, -1, -1}));
  // The same detection of A where clutter and unmapped trees are dense enough that its gate
  // expects more than the miss probability of them: no.
  EXPECT_EQ(AssociateLeftovers(p.g, p.s, {detections[0]}, {9.21, 0.01, 1.0}), (std::vector<int>{-1}));
  // Without marginals, nothing joins.
  LandmarkGraphSolution none = p.s;
  none.covariance_ok = false;
  EXPECT_EQ(AssociateLeftovers(p.g, none, {detections[0]}, settings), (std::vector<int>{-1}));
}

TEST(AssociateLeftovers, TheGateIsDeadReckonedFromTheNearestObservingKeyframe) {
  // The marginals say the far end of the chain is uncertain by 3 m (the anchor is far): the
  // loose gate holds both A and a second landmark 1.5 m away, but from keyframe 3, which saw
  // A, four precise odometry steps put the detection on A only.
  Park p;
  p.g.landmarks[4] = Eigen::Vector2d(3, 3.5);
  for (int k = 0; k < 4; ++k) p.g.observations.push_back({k, 4, p.Z(k, 4)});
  p.s.landmark_covariances[4] = 1e-3 * Eigen::Matrix2d::Identity();
  p.s.pose_covariances.assign(8, Eigen::Vector3d(9.0, 9.0, 1e-4).asDiagonal());
  EXPECT_EQ(AssociateLeftovers(p.g, p.s, {{7, p.Z(7, 0)}}, {9.21, 0.01, 1e-4}), (std::vector<int>{0}));
}

}  // namespace
}  // namespace slambox
