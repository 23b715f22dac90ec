// SE(2) composition Jacobians against central finite differences, with headings near
// +-pi (the angle difference is wrapped), and the composed covariance's closed form.
#include "core/se2.hpp"

#include <gtest/gtest.h>

#include <random>

namespace slambox {
namespace {

Eigen::Vector3d Diff(const SE2& a, const SE2& b) { return {a.x - b.x, a.y - b.y, NormalizeAngle(a.theta - b.theta)}; }

SE2 Perturb(const SE2& T, int k, double h) {
  Eigen::Vector3d v = T.vector();
  v(k) += h;
  return SE2::FromVector(v);
}

TEST(Se2, ExpLogAndAdjointAreExactInverses) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-3.0, 3.0), angle(-M_PI + 1e-6, M_PI - 1e-6);
  for (int k = 0; k < 200; ++k) {
    const SE2 T(u(rng), u(rng), k == 0 ? 0.0 : k == 1 ? 1e-12 : angle(rng));  // small-angle branch too
    EXPECT_LT(Diff(Exp(Log(T)), T).norm(), 1e-12) << k;
    const Eigen::Vector3d xi(u(rng), u(rng), angle(rng));
    EXPECT_LT((Log(Exp(xi)) - xi).norm(), 1e-12) << k;
    // SE(2)'s adjoint is exact: T Exp(xi) T^-1 = Exp(Ad(T) xi).
    EXPECT_LT(Diff(T * Exp(xi) * T.inverse(), Exp(Adjoint(T) * xi)).norm(), 1e-12) << k;
  }
  // Closed form: a quarter turn along a unit arc ends at (sin w / w, (1 - cos w) / w) * |v|.
  const SE2 arc = Exp(Eigen::Vector3d(1.0, 0.0, M_PI / 2));
  EXPECT_NEAR(arc.x, 2.0 / M_PI, 1e-15);
  EXPECT_NEAR(arc.y, 2.0 / M_PI, 1e-15);
}

TEST(Se2, ComposeJacobiansMatchFiniteDifferences) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-4.0, 4.0);
  const double h = 1e-6;
  for (int trial = 0; trial < 100; ++trial) {
    // Every fourth trial puts both headings next to +-pi, so the sum wraps.
    const double th = trial % 4 == 0 ? M_PI - 1e-3 : u(rng);
    const SE2 A(u(rng), u(rng), th), B(u(rng), u(rng), trial % 4 == 0 ? 2e-3 : u(rng));
    const ComposeJacobians J = ComposeJacobian(A, B);
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d da = Diff(Perturb(A, k, h) * B, Perturb(A, k, -h) * B) / (2 * h);
      const Eigen::Vector3d db = Diff(A * Perturb(B, k, h), A * Perturb(B, k, -h)) / (2 * h);
      EXPECT_NEAR((da - J.J_a.col(k)).norm(), 0.0, 1e-7) << "trial " << trial << " column " << k;
      EXPECT_NEAR((db - J.J_b.col(k)).norm(), 0.0, 1e-7) << "trial " << trial << " column " << k;
    }
  }
}

TEST(Se2, ComposedCovarianceOfAPureHeadingUncertainty) {
  // A at the origin with heading variance s2 only, B = (L, 0, 0): the end point moves on
  // a circle of radius L, so var(y) = L^2 s2, cov(y, theta) = L s2, var(x) = 0.
  const double s2 = 1e-4, L = 3.0;
  Eigen::Matrix3d cov_a = Eigen::Matrix3d::Zero();
  cov_a(2, 2) = s2;
  const Eigen::Matrix3d C = ComposeCovariance(SE2(), cov_a, SE2(L, 0, 0), Eigen::Matrix3d::Zero());
  EXPECT_NEAR(C(0, 0), 0.0, 1e-15);
  EXPECT_NEAR(C(1, 1), L * L * s2, 1e-15);
  EXPECT_NEAR(C(1, 2), L * s2, 1e-15);
  EXPECT_NEAR(C(2, 2), s2, 1e-15);
  // B's covariance is rotated into A's frame: a quarter turn swaps x and y.
  const Eigen::Matrix3d cov_b = Eigen::Vector3d(4e-4, 1e-4, 0).asDiagonal();
  const Eigen::Matrix3d D = ComposeCovariance(SE2(0, 0, M_PI / 2), Eigen::Matrix3d::Zero(), SE2(), cov_b);
  EXPECT_NEAR(D(0, 0), 1e-4, 1e-15);
  EXPECT_NEAR(D(1, 1), 4e-4, 1e-15);
}

}  // namespace
}  // namespace slambox
