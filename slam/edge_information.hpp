#pragma once
// Information matrices for pose-graph edges measured by ICP. The Hessian-based ICP
// covariance is optimistic (Censi 2007), so no direction may be more certain than a cap;
// directions ICP could not observe (degenerate) take the odometry's information instead.
#include <Eigen/Core>

#include "slam/icp.hpp"

namespace slambox {

struct InformationCaps {
  double sigma_xy_m = 0.005;      ///< [m] no translation direction more certain than this
  double sigma_theta_rad = 0.002; ///< [rad] nor the heading
};

/// Information over (dx, dy, dtheta) of T_target_source: inverse of r.covariance, with
/// the odometry's information projected onto r's degenerate directions, then every
/// eigenvalue of S^-1/2 Omega S^-1/2 clamped to <= 1, S = diag(caps^-2).
Eigen::Matrix3d IcpEdgeInformation(const IcpResult& r, const Eigen::Matrix3d& odometry_covariance,
                                   const InformationCaps& caps);

/// diag(sigma_xy^-2, sigma_xy^-2, sigma_theta^-2).
Eigen::Matrix3d FixedInformation(double sigma_xy_m, double sigma_theta_rad);

}  // namespace slambox
