#include "slam/pose_graph_cost.hpp"

#include <Eigen/Cholesky>
#include <cmath>

namespace slambox {

bool PoseGraphEdgeCost::Evaluate(double const* const* parameters, double* residuals,
                                 double** jacobians) const {
  const double* p_i = parameters[0];
  const double* p_j = parameters[1];
  const double c = std::cos(p_i[2]), s = std::sin(p_i[2]);
  const double dx = p_j[0] - p_i[0], dy = p_j[1] - p_i[1];
  // e = [R_i^T (t_j - t_i) - t_ij ; wrap(theta_j - theta_i - theta_ij)]
  const Eigen::Vector3d e(c * dx + s * dy - T_ij_.x, -s * dx + c * dy - T_ij_.y,
                          NormalizeAngle(p_j[2] - p_i[2] - T_ij_.theta));
  Eigen::Map<Eigen::Vector3d> r(residuals);
  r = sqrt_information_ * e;
  if (jacobians == nullptr) return true;
  // de/dpose_i = [-R_i^T, dR_i^T/dtheta (t_j - t_i); 0 0 -1],  de/dpose_j = [R_i^T, 0; 0 0 1].
  using Jacobian = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
  if (jacobians[0] != nullptr) {
    Jacobian J;
    J << -c, -s, -s * dx + c * dy,  //
        s, -c, -c * dx - s * dy,    //
        0.0, 0.0, -1.0;
    Eigen::Map<Jacobian> J_r(jacobians[0]);
    J_r = sqrt_information_ * J;
  }
  if (jacobians[1] != nullptr) {
    Jacobian J;
    J << c, s, 0.0,  //
        -s, c, 0.0,  //
        0.0, 0.0, 1.0;
    Eigen::Map<Jacobian> J_r(jacobians[1]);
    J_r = sqrt_information_ * J;
  }
  return true;
}


}  // namespace slambox
