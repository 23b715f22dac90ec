#pragma once
// Thrun's odometry noise (alpha1..alpha4, core/odometry_model.hpp) fitted to a log's own
// per-step covariances, for logs that state them (Victoria Park's preprocessed file):
// the increment covariance J M(alpha) J^T is linear in alpha, so the fit is a
// non-negative least-squares problem over the six distinct entries of every step's
// covariance (equal weights, in the file's units: m^2, m rad, rad^2).
#include <Eigen/Core>
#include <array>
#include <vector>

#include "core/se2.hpp"

namespace slambox {

struct OdometryNoiseFit {
  std::array<double, 4> alpha{};  ///< >= 0 each
  double rms_residual = 0.0;      ///< RMS over the fitted entries of (file - model)
  double rms_file = 0.0;          ///< RMS of the file's entries (scale of the residual)
};

/// `increments[k]` with its covariance `covariances[k]` over (x [m], y [m], theta [rad]).
/// Sizes must match; an empty input returns zeros.
OdometryNoiseFit FitOdometryAlpha(const std::vector<SE2>& increments, const std::vector<Eigen::Matrix3d>& covariances);

}  // namespace slambox
