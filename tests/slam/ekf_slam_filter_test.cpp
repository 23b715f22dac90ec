// The EKF-SLAM filter operations against hand-computed values and against the dense
// textbook formulas (full G, H, and the (3+2n)x(3+2n) products) on random states.
#include "slam/ekf_slam_filter.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "slam/range_bearing.hpp"

namespace slambox {
namespace {

/// A random state with `n` landmarks around the robot and a random SPD covariance.
EkfSlamState RandomState(std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  EkfSlamState s = MakeInitialState(SE2(u(rng), u(rng), 3.0 * u(rng)));
  s.mean.conservativeResize(3 + 2 * n);
  for (int j = 0; j < n; ++j) s.mean.segment<2>(3 + 2 * j) = Eigen::Vector2d(8 * u(rng), 8 * u(rng)) + Eigen::Vector2d(0.5, 0.5);
  Eigen::MatrixXd A = Eigen::MatrixXd::NullaryExpr(3 + 2 * n, 3 + 2 * n, [&] { return 0.1 * u(rng); });
  s.covariance = A * A.transpose() + 0.01 * Eigen::MatrixXd::Identity(3 + 2 * n, 3 + 2 * n);
  return s;
}

TEST(EkfSlamFilter, OneLandmarkUpdateMatchesHandComputation) {
  // Robot certain at the origin facing +x, landmark at (10, 0) with P = diag(0.04, 0.09).
  // H_m = [[1, 0], [0, 1/10]], R = diag(0.01, 1e-4):
  // S = diag(0.05, 0.001), K_m = diag(0.8, 9), nu = (0.1, 0.02)
  // -> m = (10.08, 0.18), P_m = diag(0.2 * 0.04, 0.1 * 0.09) = diag(0.008, 0.009).
  EkfSlamState s = MakeInitialState(SE2(0, 0, 0));
  s.mean.conservativeResize(5);
  s.mean.tail<2>() << 10.0, 0.0;
  s.covariance = Eigen::MatrixXd::Zero(5, 5);
  s.covariance(3, 3) = 0.04;
  s.covariance(4, 4) = 0.09;
  const Eigen::Matrix2d R = Eigen::Vector2d(0.01, 1e-4).asDiagonal();
  const ObservationPrediction p = PredictObservation(s.Pose(), s.Landmark(0));
  const EkfUpdateResult r =
      UpdateState(s, {{0, Innovation({10.1, 0.02}, p.z), p.J_z_pose, p.J_z_landmark}}, R);
  ASSERT_TRUE(r.applied);
  EXPECT_NEAR(r.nis, 0.01 / 0.05 + 0.0004 / 0.001, 1e-9);
  EXPECT_NEAR(s.mean(3), 10.08, 1e-12);
  EXPECT_NEAR(s.mean(4), 0.18, 1e-12);
  EXPECT_NEAR(s.covariance(3, 3), 0.008, 1e-12);
  EXPECT_NEAR(s.covariance(4, 4), 0.009, 1e-12);
  EXPECT_NEAR(s.covariance(3, 4), 0.0, 1e-12);
  EXPECT_NEAR((s.covariance.topLeftCorner<3, 3>()).norm(), 0.0, 1e-12);
  EXPECT_NEAR(s.mean.head<3>().norm(), 0.0, 1e-12);
}

TEST(EkfSlamFilter, PredictionEqualsDenseGPGt) {
  std::mt19937_64 rng(1);
  EkfSlamState s = RandomState(rng, 6);
  const Eigen::MatrixXd P0 = s.covariance;
  Eigen::Matrix3d J;
  J << 1, 0, -0.3, 0, 1, 0.7, 0, 0, 1;
  const Eigen::Matrix3d Q = Eigen::Vector3d(0.01, 0.02, 0.003).asDiagonal();
  PredictState(s, SE2(1, 2, 0.5), J, Q);
  Eigen::MatrixXd G = Eigen::MatrixXd::Identity(15, 15), Qfull = Eigen::MatrixXd::Zero(15, 15);
  G.topLeftCorner<3, 3>() = J;
  Qfull.topLeftCorner<3, 3>() = Q;
  EXPECT_LT((s.covariance - (G * P0 * G.transpose() + Qfull)).norm(), 1e-12);
  EXPECT_EQ(s.mean.head<3>(), Eigen::Vector3d(1, 2, 0.5));
}

TEST(EkfSlamFilter, AugmentationEqualsDenseJacobianTransform) {
  std::mt19937_64 rng(2);
  EkfSlamState s = RandomState(rng, 3);
  const Eigen::MatrixXd P0 = s.covariance;
  const Eigen::Matrix2d R = Eigen::Vector2d(0.0025, 3e-4).asDiagonal();
  const Eigen::Vector2d z(4.0, 2.9);
  const LandmarkInitialization init = InverseObservation(s.Pose(), z);
  EXPECT_EQ(AddLandmark(s, z, R), 3);
  // [x; m_new] = f(x, z): Jx = [I; Gx 0], Jz = [0; Gz]; P' = Jx P Jx^T + Jz R Jz^T.
  Eigen::MatrixXd Jx = Eigen::MatrixXd::Zero(11, 9), Jz = Eigen::MatrixXd::Zero(11, 2);
  Jx.topRows(9) = Eigen::MatrixXd::Identity(9, 9);
  Jx.block<2, 3>(9, 0) = init.J_landmark_pose;
  Jz.bottomRows<2>() = init.J_landmark_z;
  EXPECT_LT((s.covariance - (Jx * P0 * Jx.transpose() + Jz * R * Jz.transpose())).norm(), 1e-12);
  EXPECT_LT((s.Landmark(3) - init.landmark).norm(), 1e-15);
}

TEST(EkfSlamFilter, RemoveLandmarkMarginalizes) {
  std::mt19937_64 rng(4);
  EkfSlamState s = RandomState(rng, 4);
  const EkfSlamState before = s;
  RemoveLandmark(s, 1);
  ASSERT_EQ(s.NumLandmarks(), 3);
  std::vector<int> keep = {0, 1, 2, 3, 4, 7, 8, 9, 10};
  for (int r = 0; r < 9; ++r) {
    EXPECT_EQ(s.mean(r), before.mean(keep[r]));
    for (int c = 0; c < 9; ++c) EXPECT_EQ(s.covariance(r, c), before.covariance(keep[r], keep[c]));
  }
}

TEST(EkfSlamFilter, BatchedJosephUpdateEqualsDenseFormula) {
  std::mt19937_64 rng(9);
  for (int trial = 0; trial < 10; ++trial) {
    EkfSlamState s = RandomState(rng, 5);
    const EkfSlamState before = s;
    const Eigen::Matrix2d R = Eigen::Vector2d(0.01, 2e-4).asDiagonal();
    std::vector<LinearizedObservation> obs;
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(6, 13);
    Eigen::VectorXd nu(6);
    for (int q = 0; q < 3; ++q) {
      const int j = (q * 2 + trial) % 5;
      const ObservationPrediction p = PredictObservation(s.Pose(), s.Landmark(j));
      const Eigen::Vector2d v(0.05 * (q + 1), 0.01 * (q - 1));
      obs.push_back({j, v, p.J_z_pose, p.J_z_landmark});
      H.block<2, 3>(2 * q, 0) = p.J_z_pose;
      H.block<2, 2>(2 * q, 3 + 2 * j) = p.J_z_landmark;
      nu.segment<2>(2 * q) = v;
    }
    ASSERT_TRUE(UpdateState(s, obs, R).applied);
    Eigen::MatrixXd Rk = Eigen::MatrixXd::Zero(6, 6);
    for (int q = 0; q < 3; ++q) Rk.block<2, 2>(2 * q, 2 * q) = R;
    const Eigen::MatrixXd& P = before.covariance;
    const Eigen::MatrixXd S = H * P * H.transpose() + Rk;
    const Eigen::MatrixXd K = P * H.transpose() * S.inverse();
    const Eigen::MatrixXd IKH = Eigen::MatrixXd::Identity(13, 13) - K * H;
    const Eigen::MatrixXd P_ref = IKH * P * IKH.transpose() + K * Rk * K.transpose();
    Eigen::VectorXd x_ref = before.mean + K * nu;
    x_ref(2) = NormalizeAngle(x_ref(2));
    EXPECT_LT((s.covariance - P_ref).norm(), 1e-10);
    EXPECT_LT((s.mean - x_ref).norm(), 1e-10);
    EXPECT_EQ(s.covariance, s.covariance.transpose());
  }
}

}  // namespace
}  // namespace slambox
