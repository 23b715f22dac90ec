#include "slam/edge_information.hpp"

#include <Eigen/Dense>

namespace slambox {

Eigen::Matrix3d FixedInformation(double sigma_xy_m, double sigma_theta_rad) {
  return Eigen::Vector3d(1 / (sigma_xy_m * sigma_xy_m), 1 / (sigma_xy_m * sigma_xy_m),
                         1 / (sigma_theta_rad * sigma_theta_rad))
      .asDiagonal();
}

Eigen::Matrix3d IcpEdgeInformation(const IcpResult& r, const Eigen::Matrix3d& odometry_covariance,
                                   const InformationCaps& caps) {
  // Inverse covariance through r's eigenbasis (covariance = V diag(sigma^2/lambda) V^T).
  Eigen::Matrix3d omega = Eigen::Matrix3d::Zero(), degenerate = Eigen::Matrix3d::Zero();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> ec(r.covariance);
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d v = ec.eigenvectors().col(k);
    omega += v * v.transpose() / std::max(ec.eigenvalues()(k), 1e-300);
  }
  if (r.degenerate) {
    for (int k = 0; k < r.degenerate_dimensions; ++k)
      degenerate += r.eigenvectors.col(k) * r.eigenvectors.col(k).transpose();
    const Eigen::Matrix3d odo_info = (odometry_covariance + 1e-12 * Eigen::Matrix3d::Identity()).inverse();
    const Eigen::Matrix3d keep = Eigen::Matrix3d::Identity() - degenerate;
    omega = keep * omega * keep + degenerate * odo_info * degenerate;
  }
  const Eigen::Vector3d s(caps.sigma_xy_m, caps.sigma_xy_m, caps.sigma_theta_rad);  // S^-1/2
  const Eigen::Matrix3d N = s.asDiagonal() * omega * s.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> en(0.5 * (N + N.transpose()));
  Eigen::Matrix3d clamped = Eigen::Matrix3d::Zero();
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d v = en.eigenvectors().col(k);
    clamped += v * v.transpose() * std::clamp(en.eigenvalues()(k), 1e-12, 1.0);
  }
  const Eigen::Vector3d s_inv = s.cwiseInverse();
  return s_inv.asDiagonal() * clamped * s_inv.asDiagonal();
}

}  // namespace slambox
