// Range-bearing observation model and its inverse: Jacobians against central finite
// differences (bearings near +-pi included), round trip, and the wrapped innovation.
#include "slam/range_bearing.hpp"

#include <gtest/gtest.h>

#include <random>

namespace slambox {
namespace {

constexpr double kStep = 1e-6;

Eigen::Vector2d ZDiff(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return Innovation(a, b); }

/// Random pose and landmark; `near_pi` places the landmark almost straight behind the robot.
std::pair<SE2, Eigen::Vector2d> RandomCase(std::mt19937_64& rng, bool near_pi) {
  std::uniform_real_distribution<double> u(-5.0, 5.0), r(0.5, 15.0), eps(-1e-4, 1e-4);
  const SE2 pose(u(rng), u(rng), u(rng));
  const double bearing = near_pi ? M_PI + eps(rng) : u(rng);
  const double range = r(rng), heading = pose.theta + bearing;
  return {pose, pose.translation() + range * Eigen::Vector2d(std::cos(heading), std::sin(heading))};
}

TEST(RangeBearing, ObservationJacobiansMatchFiniteDifferences) {
  std::mt19937_64 rng(3);
  for (int i = 0; i < 400; ++i) {
    const auto [pose, m] = RandomCase(rng, i % 2 == 0);
    const ObservationPrediction p = PredictObservation(pose, m);
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d d = Eigen::Vector3d::Zero();
      d(k) = kStep;
      const Eigen::Vector2d fd = ZDiff(PredictObservation(SE2::FromVector(pose.vector() + d), m).z,
                                       PredictObservation(SE2::FromVector(pose.vector() - d), m).z) / (2 * kStep);
      EXPECT_LT((fd - p.J_z_pose.col(k)).norm(), 1e-6) << i;
    }
    for (int k = 0; k < 2; ++k) {
      Eigen::Vector2d d = Eigen::Vector2d::Zero();
      d(k) = kStep;
      const Eigen::Vector2d fd =
          ZDiff(PredictObservation(pose, m + d).z, PredictObservation(pose, m - d).z) / (2 * kStep);
      EXPECT_LT((fd - p.J_z_landmark.col(k)).norm(), 1e-6) << i;
    }
    EXPECT_GE(p.z.y(), -M_PI);
    EXPECT_LT(p.z.y(), M_PI);
  }
}

TEST(RangeBearing, InverseObservationJacobiansAndRoundTrip) {
  std::mt19937_64 rng(5);
  for (int i = 0; i < 400; ++i) {
    const auto [pose, m] = RandomCase(rng, i % 2 == 0);
    const Eigen::Vector2d z = PredictObservation(pose, m).z;
    const LandmarkInitialization init = InverseObservation(pose, z);
    EXPECT_LT((init.landmark - m).norm(), 1e-9);
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d d = Eigen::Vector3d::Zero();
      d(k) = kStep;
      const Eigen::Vector2d fd = (InverseObservation(SE2::FromVector(pose.vector() + d), z).landmark -
                                  InverseObservation(SE2::FromVector(pose.vector() - d), z).landmark) / (2 * kStep);
      EXPECT_LT((fd - init.J_landmark_pose.col(k)).norm(), 1e-6) << i;
    }
    for (int k = 0; k < 2; ++k) {
      Eigen::Vector2d d = Eigen::Vector2d::Zero();
      d(k) = kStep;
      const Eigen::Vector2d fd =
          (InverseObservation(pose, z + d).landmark - InverseObservation(pose, z - d).landmark) / (2 * kStep);
      EXPECT_LT((fd - init.J_landmark_z.col(k)).norm(), 1e-6) << i;
    }
  }
}

TEST(RangeBearing, InnovationWrapsTheBearing) {
  const Eigen::Vector2d nu = Innovation({2.0, M_PI - 0.01}, {1.5, -M_PI + 0.01});
  EXPECT_NEAR(nu.x(), 0.5, 1e-15);
  EXPECT_NEAR(nu.y(), -0.02, 1e-12);
  EXPECT_NEAR(Innovation({1.0, -M_PI + 0.01}, {1.0, M_PI - 0.01}).y(), 0.02, 1e-12);
}

TEST(RangeBearing, ObservationCovarianceConvertsDegrees) {
  LandmarkSensorConfig s;
  s.sigma_range_m = 0.1;
  s.sigma_bearing_deg = 2.0;
  const Eigen::Matrix2d R = ObservationCovariance(s);
  EXPECT_NEAR(R(0, 0), 0.01, 1e-15);
  EXPECT_NEAR(R(1, 1), std::pow(2.0 * M_PI / 180.0, 2), 1e-15);
  EXPECT_EQ(R(0, 1), 0.0);
}

}  // namespace
}  // namespace slambox
