#include "slam/icp_prior.hpp"

#include <Eigen/Cholesky>

namespace slambox {

Eigen::Vector3d PriorResidual(const IcpPrior& prior, const SE2& T) {
  return {T.x - prior.mean.x, T.y - prior.mean.y, NormalizeAngle(T.theta - prior.mean.theta)};
}

SE2 FuseWithPrior(const SE2& T_scan, const Eigen::Matrix3d& scan_information, const IcpPrior& prior) {
  const Eigen::Matrix3d H = scan_information + prior.information;
  const Eigen::Vector3d step = -H.ldlt().solve(prior.information * PriorResidual(prior, T_scan));
  if (!step.allFinite()) return T_scan;  // both informations zero along some direction
  return SE2(T_scan.x + step.x(), T_scan.y + step.y(), T_scan.theta + step.z());
}

}  // namespace slambox
