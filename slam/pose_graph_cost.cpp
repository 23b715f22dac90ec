#include "slam/pose_graph_cost.hpp"

#include <Eigen/Cholesky>
#include <cmath>

namespace slambox {

bool PoseGraphEdgeCost::Evaluate(double const* const* parameters, double* residuals,
                                 double** jacobians) const {
  const Eigen::Vector2d t_i(parameters[0][0], parameters[0][1]);
  const double theta_i = parameters[1][0];
  const Eigen::Vector2d t_j(parameters[2][0], parameters[2][1]);
  const double theta_j = parameters[3][0];

  const double c = std::cos(theta_i), s = std::sin(theta_i);
  const Eigen::Matrix2d Rt_i = RotationMatrix(theta_i).transpose();
  const Eigen::Vector2d dt = t_j - t_i;
  Eigen::Vector3d e;
  e.head<2>() = Rt_i * dt - T_ij_.translation();
  e.z() = NormalizeAngle(theta_j - theta_i - T_ij_.theta);
  Eigen::Map<Eigen::Vector3d> r(residuals);
  r = sqrt_information_ * e;
  if (jacobians == nullptr) return true;

  // de/dt_i = [-R_i^T; 0], de/dtheta_i = [dR_i^T/dtheta (t_j - t_i); -1],
  // de/dt_j = [R_i^T; 0],  de/dtheta_j = [0; 0; 1]; then r = U e.
  if (jacobians[0] != nullptr) {
    Eigen::Matrix<double, 3, 2> J = Eigen::Matrix<double, 3, 2>::Zero();
    J.topRows<2>() = -Rt_i;
    Eigen::Map<Eigen::Matrix<double, 3, 2, Eigen::RowMajor>> J_r(jacobians[0]);
    J_r = sqrt_information_ * J;
  }
  if (jacobians[1] != nullptr) {
    const Eigen::Vector3d J(-s * dt.x() + c * dt.y(), -c * dt.x() - s * dt.y(), -1.0);
    Eigen::Map<Eigen::Vector3d> J_r(jacobians[1]);
    J_r = sqrt_information_ * J;
  }
  if (jacobians[2] != nullptr) {
    Eigen::Matrix<double, 3, 2> J = Eigen::Matrix<double, 3, 2>::Zero();
    J.topRows<2>() = Rt_i;
    Eigen::Map<Eigen::Matrix<double, 3, 2, Eigen::RowMajor>> J_r(jacobians[2]);
    J_r = sqrt_information_ * J;
  }
  if (jacobians[3] != nullptr) {
    Eigen::Map<Eigen::Vector3d> J_r(jacobians[3]);
    J_r = sqrt_information_.col(2);
  }
  return true;
}

bool SqrtInformation(const Eigen::Matrix3d& information, Eigen::Matrix3d* sqrt_information) {
  if (!information.allFinite()) return false;
  if (!information.isApprox(information.transpose(), 1e-12)) return false;
  Eigen::LLT<Eigen::Matrix3d> llt(information);
  if (llt.info() != Eigen::Success) return false;
  const Eigen::Matrix3d U = llt.matrixU();
  if (!(U.diagonal().array() > 0.0).all()) return false;
  *sqrt_information = U;
  return true;
}

void DcsLoss::Evaluate(double s, double rho[3]) const {
  if (s <= phi_) {
    rho[0] = s;
    rho[1] = 1.0;
    rho[2] = 0.0;
    return;
  }
  const double d = phi_ + s;
  rho[0] = 3.0 * phi_ - 4.0 * phi_ * phi_ / d;
  rho[1] = 4.0 * phi_ * phi_ / (d * d);
  rho[2] = -8.0 * phi_ * phi_ / (d * d * d);
}

}  // namespace slambox
