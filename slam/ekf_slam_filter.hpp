#pragma once
// The EKF-SLAM Gaussian over robot and map, x = (x, y, theta, m1x, m1y, ..., mnx, mny),
// and its three operations (Thrun, Prob. Robotics, Table 10.1; Bailey's ekfslam):
// prediction touching only the robot rows (O(n)), augmentation by the inverse
// observation model with its cross covariances (O(n)), and a batched range-bearing
// update in Joseph form (O(n^2) per observation, no (3+2n)^3 work).
#include <Eigen/Core>
#include <vector>

#include "core/se2.hpp"

namespace slambox {

struct EkfSlamState {
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(3);
  Eigen::MatrixXd covariance = Eigen::MatrixXd::Zero(3, 3);

  int NumLandmarks() const { return static_cast<int>(mean.size() - 3) / 2; }
  SE2 Pose() const { return {mean(0), mean(1), mean(2)}; }
  Eigen::Vector2d Landmark(int index) const { return mean.segment<2>(3 + 2 * index); }
  Eigen::Matrix2d LandmarkCovariance(int index) const {
    return covariance.block<2, 2>(3 + 2 * index, 3 + 2 * index);
  }
};

/// A robot at `start` with zero covariance and no landmarks.
EkfSlamState MakeInitialState(const SE2& start);

/// x' = predicted_pose, P_rr' = J P_rr J^T + Q_pose, P_rm' = J P_rm (the map block is
/// untouched). J = J_pose_pose (FEJ callers pass it evaluated at first estimates),
/// Q_pose = J_pose_increment M J_pose_increment^T.
void PredictState(EkfSlamState& state, const SE2& predicted_pose, const Eigen::Matrix3d& J_pose_pose,
                  const Eigen::Matrix3d& Q_pose);

/// Appends the landmark m = g(x, z) (InverseObservation) with
/// P_mm = Gx P_rr Gx^T + Gz R Gz^T and P_m* = Gx P_r* (Bailey's augment). Returns its index.
int AddLandmark(EkfSlamState& state, const Eigen::Vector2d& z, const Eigen::Matrix2d& R);

/// Marginalizes landmark `index` out (drops its rows and columns); later indices shift down.
void RemoveLandmark(EkfSlamState& state, int index);

/// One range-bearing measurement of landmark `landmark` with the Jacobians of h at the
/// linearization point (current estimate, or first estimates for FEJ-EKF).
struct LinearizedObservation {
  int landmark = 0;
  Eigen::Vector2d innovation = Eigen::Vector2d::Zero();  ///< z - h(x̂), bearing wrapped
  Eigen::Matrix<double, 2, 3> J_z_pose = Eigen::Matrix<double, 2, 3>::Zero();
  Eigen::Matrix2d J_z_landmark = Eigen::Matrix2d::Zero();
};

struct EkfUpdateResult {
  bool applied = false;  ///< false: the innovation covariance was not positive definite
  double nis = 0.0;      ///< joint ν^T S^-1 ν of the batch
  int dof = 0;           ///< 2 * number of observations
  int iterations = 0;    ///< linearizations used (IteratedUpdateState; 1 = the plain EKF step)
};

/// Batched update with all observations of one scan, Joseph form
/// P' = (I - K H) P (I - K H)^T + K R K^T, K = P H^T S^-1, S = H P H^T + R; H is sparse
/// (two 2x3 and 2x2 blocks per row pair), so every product with H is O(n) and the two
/// dense products are O(n^2 k) for k observations. R is the per-observation covariance.
EkfUpdateResult UpdateState(EkfSlamState& state, const std::vector<LinearizedObservation>& observations,
                            const Eigen::Matrix2d& R);

/// The same update for the right-invariant error of the Invariant EKF (Barrau & Bonnabel
/// 2015, "An EKF-SLAM algorithm with consistency properties"). The state is an element of
/// SE_{1+n}(2), (R(theta), p_r, p_1, ..., p_n), and its error xi is a world-frame motion of
/// all of it: x = exp(xi) x̂ rotates every position q about the origin by xi_theta, then
/// moves it by V(xi_theta) xi_q. To first order e = x - x̂ = T(x̂) xi with T = I + c e_theta^T,
/// c = J q̂ on the rows of each position q (J = [0 -1; 1 0]), 0 on the heading's.
/// - Prediction needs nothing new: the standard F at (x̂, x̂') is T(x̂') T(x̂)^-1, i.e. the
///   invariant error's propagation is the identity (PredictState with J_pose_pose as is).
/// - A body-frame observation h(R^T (p_i - p_r)) has H T = (0, H_r, H_i): no heading column,
///   at any estimate, so the rotation about the origin and the translation of everything
///   stay unobservable (standard EKF-SLAM gains information along them: its Jacobians
///   follow the moving estimate; Huang et al. 2010).
/// So the batch's gain and Joseph update are UpdateState's (a Kalman update does not depend
/// on linear coordinates); the correction xi = T(x̂)^-1 K nu is then retracted exactly,
/// theta' = theta + xi_theta, q' = R(xi_theta) q̂ + V(xi_theta) xi_q, and the covariance of xi
/// is expressed at the new estimate: P' = A P A^T, A = T(x̂') T(x̂)^-1 = I + (c(x̂') - c(x̂)) e_theta^T.
/// (A merge's conditioning on m_a = m_b stays a standard update: that constraint is in the
/// world frame, its Jacobian in invariant coordinates has a heading column J (m_a - m_b), and
/// retracting it measured worse; slam/README_landmark_slam.md.)
EkfUpdateResult InvariantUpdateState(EkfSlamState& state, const std::vector<LinearizedObservation>& observations,
                                     const Eigen::Matrix2d& R);

/// One range-bearing measurement z of landmark `landmark` (the iterated update linearizes it itself).
struct LandmarkMeasurement {
  int landmark = 0;
  Eigen::Vector2d z = Eigen::Vector2d::Zero();
};

/// Iterated EKF update (Bell & Cathey 1993; Bar-Shalom et al. 2001, sec. 10.5.2): Gauss-Newton
/// on the posterior of the prior N(x̂, P) and the batch's likelihood, relinearizing h at each
/// iterate x_i (x_0 = x̂):
///   x_{i+1} = x̂ + K_i (z - h(x_i) - H_i (x̂ - x_i)),  K_i = P H_i^T (H_i P H_i^T + R)^-1,
/// bearings and the heading difference wrapped, until a step moves the state less than 1e-9
/// (m, rad) or `iterations` are done; P' in Joseph form with the last K_i and H_i. The NIS is
/// the one at x̂ (the filter's consistency). iterations = 1 is UpdateState at x̂, bit for bit.
///
/// step_gate_chi2 > 0 iterates only an update the linearization at x̂ cannot carry: past the
/// first (EKF) step δ only if its robot part is improbable under the prior,
/// δ_r^T P_rr^-1 δ_r >= step_gate_chi2 (e.g. a re-sighting after a long drift that turns the
/// robot by many of its heading sigmas, where h's curvature over the step is not negligible).
/// Below the gate the result is UpdateState's, bit for bit.
EkfUpdateResult IteratedUpdateState(EkfSlamState& state, const std::vector<LandmarkMeasurement>& measurements,
                                    const Eigen::Matrix2d& R, int iterations, double step_gate_chi2 = 0.0);

}  // namespace slambox
