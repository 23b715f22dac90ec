// Thrun's odometry model: Decompose/Compose round trip and the Jacobians of PredictMotion
// against central finite differences, including headings near +-pi.
#include "core/odometry_model.hpp"

#include <gtest/gtest.h>

#include <random>

namespace slambox {
namespace {

constexpr double kStep = 1e-6;

Eigen::Vector3d Diff(const SE2& a, const SE2& b) {  // a - b with the angle wrapped
  return {a.x - b.x, a.y - b.y, NormalizeAngle(a.theta - b.theta)};
}

TEST(OdometryModel, ComposeInvertsDecompose) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int i = 0; i < 200; ++i) {
    const SE2 delta(u(rng), u(rng), u(rng));
    const SE2 back = Compose(Decompose(delta));
    EXPECT_NEAR(Diff(back, delta).norm(), 0.0, 1e-12);
  }
  const OdometryIncrement spin = Decompose(SE2(0.0, 0.0, 0.3));
  EXPECT_EQ(spin.rot1, 0.0);
  EXPECT_NEAR(spin.rot2, 0.3, 1e-15);
}

TEST(OdometryModel, JacobiansMatchFiniteDifferencesIncludingNearPi) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-2.0, 2.0), eps(-1e-3, 1e-3);
  for (int i = 0; i < 300; ++i) {
    // A third of the cases sit near the +-pi seam of the heading.
    const double theta = i % 3 == 0 ? M_PI + eps(rng) : i % 3 == 1 ? -M_PI + eps(rng) : u(rng);
    const SE2 pose(u(rng), u(rng), theta);
    const OdometryIncrement inc{0.5 * u(rng), std::abs(u(rng)), 0.5 * u(rng)};
    const MotionPrediction p = PredictMotion(pose, inc);
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d d = Eigen::Vector3d::Zero();
      d(k) = kStep;
      const SE2 plus = PredictMotion(SE2::FromVector(pose.vector() + d), inc).pose;
      const SE2 minus = PredictMotion(SE2::FromVector(pose.vector() - d), inc).pose;
      EXPECT_LT((Diff(plus, minus) / (2 * kStep) - p.J_pose_pose.col(k)).norm(), 1e-6) << i << " " << k;
      OdometryIncrement ip = inc, im = inc;
      (k == 0 ? ip.rot1 : k == 1 ? ip.trans : ip.rot2) += kStep;
      (k == 0 ? im.rot1 : k == 1 ? im.trans : im.rot2) -= kStep;
      const Eigen::Vector3d fd = Diff(PredictMotion(pose, ip).pose, PredictMotion(pose, im).pose) / (2 * kStep);
      EXPECT_LT((fd - p.J_pose_increment.col(k)).norm(), 1e-6) << i << " " << k;
    }
    EXPECT_GE(p.pose.theta, -M_PI);
    EXPECT_LT(p.pose.theta, M_PI);
  }
}

TEST(OdometryModel, IncrementCovarianceIsThrunsTable56) {
  const OdometryIncrement u{0.2, 1.5, -0.1};
  const Eigen::Matrix3d M = IncrementCovariance(u, {0.1, 0.2, 0.3, 0.4});
  EXPECT_NEAR(M(0, 0), 0.1 * 0.04 + 0.2 * 2.25, 1e-15);
  EXPECT_NEAR(M(1, 1), 0.3 * 2.25 + 0.4 * (0.04 + 0.01), 1e-15);
  EXPECT_NEAR(M(2, 2), 0.1 * 0.01 + 0.2 * 2.25, 1e-15);
  EXPECT_EQ(M(0, 1), 0.0);
}

}  // namespace
}  // namespace slambox
