#pragma once
// The likelihood of one landmark scan under an EKF-SLAM Gaussian, whatever the filter then
// decides to pair: the Poisson multi-object likelihood (Mahler 2007, "Statistical
// Multisource-Multitarget Information Fusion", the PHD filter's update; the densities are
// Reid 1979's). Each detection z_i comes from a false-detection field of density lambda
// per m^2 (clutter and landmarks not yet mapped; in range-bearing coordinates lambda r_i,
// as dx dy = r dr dbearing) or from a mapped landmark j, which is detected with
// probability w_j (P_D at its range times its probability of existing) and then falls at
// N(z; h_j, S_j), S_j its innovation covariance. Up to a constant shared by every filter
// that sees the same scan,
//   log p(Z) = sum_i log(lambda r_i + sum_j w_j N(z_i; h_j, S_j)) - sum_j w_j g_j,
// g_j the probability that landmark j lies inside range and field of view: a landmark
// expected in view and not seen costs its expected detections (negative information).
// Two filters that differ in one association decision (a loop closure) are compared by the
// sum of this over the scans that follow (slam/ekf_slam.hpp, closure_test).
#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "slam/ekf_slam_filter.hpp"

namespace slambox {

struct ScanLikelihoodModel {
  double false_density_per_m2 = 0.0;  ///< [1/m^2] clutter and new landmarks per scan
  double range_max_m = 1e9;           ///< [m] the detector's reach
  double half_fov_rad = M_PI;         ///< [rad] half its field of view
};

/// Probability that a landmark predicted at z = (range, bearing) with covariance C (the
/// innovation covariance less the sensor noise) lies within range_max and |bearing| <
/// half_fov: the product of the two normal marginals' masses (1 in bearing for 360 deg).
double ProbabilityInView(const Eigen::Vector2d& z_predicted, const Eigen::Matrix2d& C, double range_max_m,
                         double half_fov_rad);

/// log p(Z) above for the scan z, sensor noise R, and per landmark of `state` its
/// detection probability w_j (P_D times existence).
double ScanLogLikelihood(const EkfSlamState& state, const std::vector<Eigen::Vector2d>& z, const Eigen::Matrix2d& R,
                         const std::vector<double>& p_detect, const ScanLikelihoodModel& model);

}  // namespace slambox
