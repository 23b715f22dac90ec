// The Invariant EKF update (InvariantUpdateState, Barrau & Bonnabel 2015) against a dense
// reference: the Kalman correction mapped to the right-invariant error, retracted with the
// matrix exponential of SE(2) per position, the covariance carried by T(x̂') T(x̂)^-1; and
// the property it exists for: no information along the unobservable directions (rotation of
// everything about the origin, translation of everything) at the moving estimate.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <unsupported/Eigen/MatrixFunctions>

#include "slam/ekf_slam_filter.hpp"
#include "slam/range_bearing.hpp"

namespace slambox {
namespace {

constexpr int kLandmarks = 5, kDim = 3 + 2 * kLandmarks;

EkfSlamState RandomState(std::mt19937_64& rng, double heading) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  EkfSlamState s = MakeInitialState(SE2(3 * u(rng), 3 * u(rng), heading));
  s.mean.conservativeResize(kDim);
  for (int j = 0; j < kLandmarks; ++j) s.mean.segment<2>(3 + 2 * j) = Eigen::Vector2d(8 * u(rng), 8 * u(rng));
  const Eigen::MatrixXd A = Eigen::MatrixXd::NullaryExpr(kDim, kDim, [&] { return 0.1 * u(rng); });
  s.covariance = A * A.transpose() + 0.01 * Eigen::MatrixXd::Identity(kDim, kDim);
  return s;
}

/// Three observations of landmarks 0, 2, 4 with innovations `nu` and the dense H.
struct Batch {
  std::vector<LinearizedObservation> obs;
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(6, kDim);
  Eigen::VectorXd nu = Eigen::VectorXd::Zero(6);
};
Batch MakeBatch(const EkfSlamState& s, std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Batch b;
  for (int q = 0; q < 3; ++q) {
    const ObservationPrediction p = PredictObservation(s.Pose(), s.Landmark(2 * q));
    const Eigen::Vector2d v(0.2 * n(rng), 0.03 * n(rng));
    b.obs.push_back({2 * q, v, p.J_z_pose, p.J_z_landmark});
    b.H.block<2, 3>(2 * q, 0) = p.J_z_pose;
    b.H.block<2, 2>(2 * q, 3 + 2 * (2 * q)) = p.J_z_landmark;
    b.nu.segment<2>(2 * q) = v;
  }
  return b;
}

/// T(x) = I + c e_theta^T, c = J q on every position's rows.
Eigen::MatrixXd T(const Eigen::VectorXd& x) {
  Eigen::MatrixXd t = Eigen::MatrixXd::Identity(kDim, kDim);
  for (int k = 0; k < kDim; k += (k == 0 ? 3 : 2)) {
    t(k, 2) = -x(k + 1);
    t(k + 1, 2) = x(k);
  }
  return t;
}

/// Directions nothing observes at x: translation in x, in y, rotation about the origin.
Eigen::MatrixXd Unobservable(const Eigen::VectorXd& x) {
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(kDim, 3);
  for (int k = 0; k < kDim; k += (k == 0 ? 3 : 2)) N.block<2, 2>(k, 0).setIdentity();
  N.col(2) = T(x).col(2);  // e_theta + c(x)
  return N;
}

const Eigen::Matrix2d kR = Eigen::Vector2d(0.01, 3e-4).asDiagonal();

TEST(EkfInvariant, UpdateEqualsDenseGroupRetraction) {
  std::mt19937_64 rng(3);
  int crossed = 0;
  for (int trial = 0; trial < 20; ++trial) {
    // Half the trials start 1 mrad below +pi: their corrections cross the wrap.
    EkfSlamState s = RandomState(rng, trial % 2 ? M_PI - 1e-3 : 0.4 * trial);
    const EkfSlamState before = s;
    const Batch b = MakeBatch(s, rng);
    ASSERT_TRUE(InvariantUpdateState(s, b.obs, kR).applied);

    const Eigen::MatrixXd& P = before.covariance;
    Eigen::MatrixXd Rk = Eigen::MatrixXd::Zero(6, 6);
    for (int q = 0; q < 3; ++q) Rk.block<2, 2>(2 * q, 2 * q) = kR;
    const Eigen::MatrixXd K = P * b.H.transpose() * (b.H * P * b.H.transpose() + Rk).inverse();
    const Eigen::MatrixXd IKH = Eigen::MatrixXd::Identity(kDim, kDim) - K * b.H;
    const Eigen::MatrixXd P_joseph = IKH * P * IKH.transpose() + K * Rk * K.transpose();
    const Eigen::VectorXd xi = T(before.mean).inverse() * (K * b.nu);
    // exp(xi) x̂ position by position: the SE(2) matrix exponential of (xi_q, xi_theta).
    Eigen::VectorXd x_ref = before.mean;
    x_ref(2) = NormalizeAngle(before.mean(2) + xi(2));
    for (int k = 0; k < kDim; k += (k == 0 ? 3 : 2)) {
      Eigen::Matrix3d tangent = Eigen::Matrix3d::Zero();
      tangent(0, 1) = -xi(2);
      tangent(1, 0) = xi(2);
      tangent.block<2, 1>(0, 2) = xi.segment<2>(k);
      const Eigen::Matrix3d g = tangent.exp();
      x_ref.segment<2>(k) = g.topLeftCorner<2, 2>() * before.mean.segment<2>(k) + g.block<2, 1>(0, 2);
    }
    const Eigen::MatrixXd A = T(x_ref) * T(before.mean).inverse();
    const Eigen::MatrixXd P_ref = A * P_joseph * A.transpose();

    EXPECT_LT((s.mean - x_ref).norm(), 1e-10) << "trial " << trial;
    EXPECT_LT((s.covariance - P_ref).norm(), 1e-10) << "trial " << trial;
    EXPECT_EQ(s.covariance, s.covariance.transpose());
    EXPECT_GE(s.mean(2), -M_PI);
    EXPECT_LT(s.mean(2), M_PI);
    crossed += before.mean(2) > 3 && s.mean(2) < 0 ? 1 : 0;
  }
  EXPECT_GE(crossed, 2);  // the wrap was exercised
}

TEST(EkfInvariant, ObservationJacobianHasNoHeadingColumnInInvariantCoordinates) {
  // H T(x̂) = (0, H_r, H_i): at any estimate, rotating everything about the origin leaves
  // every body-frame observation unchanged.
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 10; ++trial) {
    const EkfSlamState s = RandomState(rng, 0.7 * trial - 3.0);
    const Batch b = MakeBatch(s, rng);
    const Eigen::MatrixXd HT = b.H * T(s.mean);
    EXPECT_LT(HT.col(2).norm(), 1e-12);
    EXPECT_LT((b.H * Unobservable(s.mean)).norm(), 1e-12);
  }
}

TEST(EkfInvariant, NoInformationGainedAlongUnobservableDirections) {
  // Information Y = P^-1 along N: N(x̂')^T Y' N(x̂') = N(x̂)^T Y N(x̂) for the invariant update;
  // the standard EKF, whose covariance stays attached to the old estimate, gains some.
  std::mt19937_64 rng(7);
  double standard_gain = 0.0;
  for (int trial = 0; trial < 10; ++trial) {
    EkfSlamState inv = RandomState(rng, 0.5 * trial - 2.0);
    EkfSlamState std_ekf = inv;
    const EkfSlamState before = inv;
    const Batch b = MakeBatch(inv, rng);
    ASSERT_TRUE(InvariantUpdateState(inv, b.obs, kR).applied);
    ASSERT_TRUE(UpdateState(std_ekf, b.obs, kR).applied);
    const auto info = [](const EkfSlamState& s) {
      const Eigen::MatrixXd N = Unobservable(s.mean);
      return Eigen::Matrix3d(N.transpose() * s.covariance.inverse() * N);
    };
    const Eigen::Matrix3d prior = info(before);
    EXPECT_LT((info(inv) - prior).norm(), 1e-8 * prior.norm()) << "trial " << trial;
    standard_gain = std::max(standard_gain, (info(std_ekf) - prior).norm() / prior.norm());
  }
  EXPECT_GT(standard_gain, 1e-3);  // what the invariant error removes
}

TEST(EkfInvariant, ZeroInnovationChangesNothingButTheCovariance) {
  std::mt19937_64 rng(11);
  EkfSlamState s = RandomState(rng, -2.5);
  const EkfSlamState before = s;
  Batch b = MakeBatch(s, rng);
  for (auto& o : b.obs) o.innovation.setZero();
  EkfSlamState plain = s;
  ASSERT_TRUE(InvariantUpdateState(s, b.obs, kR).applied);
  ASSERT_TRUE(UpdateState(plain, b.obs, kR).applied);
  EXPECT_EQ(s.mean, before.mean);
  EXPECT_LT((s.covariance - plain.covariance).norm(), 1e-15);  // A = I when nothing moves
}

}  // namespace
}  // namespace slambox
