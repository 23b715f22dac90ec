#pragma once
// The per-landmark EKF of FastSLAM (Thrun, Prob. Robotics, Table 13.1, lines 9-16) and
// FastSLAM 2.0's pose proposal (Montemerlo et al. 2003, Sec. 3; Thrun, Table 13.3),
// on the shared range-bearing model (slam/range_bearing.hpp).
#include <Eigen/Core>

#include "core/se2.hpp"
#include "slam/landmark_tree.hpp"

namespace slambox {

/// log N(innovation; 0, S) = -log(2 pi) - 1/2 log det S - 1/2 nu^T S^-1 nu.
double GaussianLogLikelihood(const Eigen::Vector2d& innovation, const Eigen::Matrix2d& S);

/// The measurement of a landmark from a known pose: innovation nu = z - h(mu, x),
/// Q = H Sigma H^T + R with H = dh/dm, and log N(nu; 0, Q) (FastSLAM 1.0's weight).
struct LandmarkMeasurement {
  Eigen::Vector2d innovation;
  Eigen::Matrix2d H;  ///< J_z_landmark
  Eigen::Matrix2d Q;  ///< innovation covariance [m^2, m rad; m rad, rad^2]
  double log_likelihood = 0.0;
};
LandmarkMeasurement MeasureLandmark(const SE2& pose, const LandmarkGaussian& landmark, const Eigen::Vector2d& z,
                                    const Eigen::Matrix2d& R);

/// EKF update: K = Sigma H^T Q^-1, mu' = mu + K nu, Sigma' = (I - K H) Sigma (symmetrized).
/// The counter is left unchanged.
LandmarkGaussian UpdateLandmark(const LandmarkGaussian& landmark, const LandmarkMeasurement& m);

/// A new landmark from one observation at a known pose: mu = h^-1(z, x),
/// Sigma = J R J^T with J = d h^-1 / dz (= H^-1 R H^-T); counter 1.
LandmarkGaussian InitializeLandmark(const SE2& pose, const Eigen::Vector2d& z, const Eigen::Matrix2d& R);

/// FastSLAM 2.0's Gaussian over the new pose: the motion prediction, then refined by each
/// associated observation in turn.
struct PoseProposal {
  SE2 mean;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

/// Log of the predictive likelihood N(z; h(mu, x_mean), L), L = H_x P H_x^T + H_m Sigma H_m^T + R
/// (Montemerlo 2003, eq. 21 / Thrun 13.3 line 21): the association score and weight factor.
double ProposalLogLikelihood(const PoseProposal& proposal, const LandmarkGaussian& landmark,
                             const Eigen::Vector2d& z, const Eigen::Matrix2d& R);

/// Conditions the proposal on z seen at `landmark` (Kalman form of Thrun 13.3 lines
/// 12-13, which also works for a singular P): K = P H_x^T L^-1, mean += K nu,
/// P = (I - K H_x) P. Returns the same log-likelihood as ProposalLogLikelihood.
double ConditionProposal(PoseProposal& proposal, const LandmarkGaussian& landmark, const Eigen::Vector2d& z,
                         const Eigen::Matrix2d& R);

/// N(z; z_hat, L) of one landmark, prepared once per scan and evaluated for every
/// observation during data association (L as in ProposalLogLikelihood; with a zero pose
/// covariance it is FastSLAM 1.0's Q).
struct PredictedMeasurement {
  Eigen::Vector2d z_hat;
  Eigen::Matrix2d L_inverse;
  double log_normalizer = 0.0;  ///< -log(2 pi) - log det(L) / 2
};
PredictedMeasurement PredictMeasurement(const PoseProposal& prior, const LandmarkGaussian& landmark,
                                        const Eigen::Matrix2d& R);
inline double LogLikelihood(const PredictedMeasurement& p, const Eigen::Vector2d& z) {
  const Eigen::Vector2d nu(z.x() - p.z_hat.x(), NormalizeAngle(z.y() - p.z_hat.y()));
  return p.log_normalizer - 0.5 * nu.dot(p.L_inverse * nu);
}

}  // namespace slambox
