#include "slam/landmark_edge_cost.hpp"

#include <Eigen/Cholesky>
#include <cmath>

namespace slambox {

Eigen::Vector2d LandmarkEdgeError(const Eigen::Vector3d& pose, const Eigen::Vector2d& l_world, const Eigen::Vector2d& z) {
  const double c = std::cos(pose.z()), s = std::sin(pose.z());
  const double dx = l_world.x() - pose.x(), dy = l_world.y() - pose.y();
  return {c * dx + s * dy - z.x(), -s * dx + c * dy - z.y()};
}

bool LandmarkEdgeCost::Evaluate(double const* const* parameters, double* residuals, double** jacobians) const {
  const double* p = parameters[0];
  const double* l = parameters[1];
  const double c = std::cos(p[2]), s = std::sin(p[2]);
  const double dx = l[0] - p[0], dy = l[1] - p[1];
  // e = R^T d - z with d = l - t and R^T = [c s; -s c]. No angle appears in e, so no wrap:
  // e is smooth in theta everywhere (also across +-pi).
  const Eigen::Vector2d e(c * dx + s * dy - z_.x(), -s * dx + c * dy - z_.y());
  Eigen::Map<Eigen::Vector2d> r(residuals);
  r = sqrt_information_ * e;
  if (jacobians == nullptr) return true;
  // de/dt = -R^T, de/dtheta = dR^T/dtheta d = [-s c; -c -s] d, de/dl = R^T.
  using Jacobian23 = Eigen::Matrix<double, 2, 3, Eigen::RowMajor>;
  using Jacobian22 = Eigen::Matrix<double, 2, 2, Eigen::RowMajor>;
  if (jacobians[0] != nullptr) {
    Jacobian23 J;
    J << -c, -s, -s * dx + c * dy,  //
        s, -c, -c * dx - s * dy;
    Eigen::Map<Jacobian23> J_r(jacobians[0]);
    J_r = sqrt_information_ * J;
  }
  if (jacobians[1] != nullptr) {
    Jacobian22 J;
    J << c, s,  //
        -s, c;
    Eigen::Map<Jacobian22> J_r(jacobians[1]);
    J_r = sqrt_information_ * J;
  }
  return true;
}


}  // namespace slambox
