// Thrun's odometry model: Decompose/Compose round trip and the Jacobians of PredictMotion
// against central finite differences, including headings near +-pi.
#include "core/odometry_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
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

TEST(OdometryModel, DecomposeReadsBackwardMotion) {
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int i = 0; i < 200; ++i) {
    const SE2 delta(u(rng), u(rng), u(rng));
    const OdometryIncrement s = Decompose(delta);
    EXPECT_LE(std::abs(s.rot1), M_PI / 2 + 1e-12);
    EXPECT_NEAR(Diff(Compose(s), delta).norm(), 0.0, 1e-12);
    EXPECT_EQ(s.trans < 0, delta.x < 0);
  }
  // A turn in place with a tiny backward slip: rot1 = 0, not pi.
  const SE2 slip(-1e-3, 0.0, 0.02);
  const OdometryIncrement s = Decompose(slip);
  EXPECT_NEAR(s.rot1, 0.0, 1e-15);
  EXPECT_NEAR(s.trans, -1e-3, 1e-15);
  EXPECT_NEAR(s.rot2, 0.02, 1e-15);
}

TEST(OdometryModel, DecomposeTakesTheShorterSecondRotation) {
  // rot2 = theta - rot1 wrapped to [-pi, pi): 3.0 + atan(0.5) = 3.46 rad is -2.82 rad, and the
  // noise model's a1 rot2^2 term uses the shorter rotation (Thrun Table 5.6 with wrapped angles).
  const OdometryIncrement u = Decompose(SE2(1.0, -0.5, 3.0));
  EXPECT_NEAR(u.rot1, -std::atan(0.5), 1e-15);
  EXPECT_NEAR(u.rot2, 3.0 + std::atan(0.5) - 2 * M_PI, 1e-12);
  const Eigen::Matrix3d M = IncrementCovariance(u, {0.1, 0.0, 0.0, 0.0});
  EXPECT_NEAR(M(2, 2), 0.1 * std::pow(3.0 + std::atan(0.5) - 2 * M_PI, 2), 1e-12);
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> x(-3.0, 3.0), theta(-M_PI, M_PI);
  for (int i = 0; i < 200; ++i) {
    const OdometryIncrement r = Decompose(SE2(x(rng), x(rng), theta(rng)));
    EXPECT_GE(r.rot2, -M_PI);
    EXPECT_LT(r.rot2, M_PI);
  }
}

TEST(OdometryModel, JacobiansMatchFiniteDifferencesIncludingNearPi) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-2.0, 2.0), eps(-1e-3, 1e-3);
  for (int i = 0; i < 300; ++i) {
    // A third of the cases sit near the +-pi seam of the heading.
    const double theta = i % 3 == 0 ? M_PI + eps(rng) : i % 3 == 1 ? -M_PI + eps(rng) : u(rng);
    const SE2 pose(u(rng), u(rng), theta);
    const OdometryIncrement inc{0.5 * u(rng), u(rng), 0.5 * u(rng)};  // trans < 0: backwards
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
