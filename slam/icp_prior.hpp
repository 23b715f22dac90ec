#pragma once
// A Gaussian prior on an ICP solution (e.g. the wheel-odometry guess with the motion
// model's covariance), fused into each ICP iteration: directions the scan constrains
// well follow the scan, degenerate or ambiguous ones follow the prior.
#include <Eigen/Core>

#include "core/se2.hpp"

namespace slambox {

struct IcpPrior {
  SE2 mean;                                               ///< prior T_target_source
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();  ///< over (x [m], y [m], theta [rad])
};

/// e(T) = (x - x0, y - y0, wrap(theta - theta0)) in the coordinates the covariance of a
/// pose propagated by the motion model is expressed in; de/d(x, y, theta) = I.
Eigen::Vector3d PriorResidual(const IcpPrior& prior, const SE2& T);

/// Minimizer of (x - x_scan)^T A (x - x_scan) + e(x)^T Omega e(x), x = (x, y, theta):
/// the scan's solution for fixed pairs, its information A, and the prior. Both terms are
/// quadratic in x (the heading residual wrapped), so one Gauss-Newton step from x_scan is
/// exact: x = x_scan - (A + Omega)^-1 Omega e(x_scan).
SE2 FuseWithPrior(const SE2& T_scan, const Eigen::Matrix3d& scan_information, const IcpPrior& prior);

}  // namespace slambox
