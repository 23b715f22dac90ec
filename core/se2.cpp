#include "core/se2.hpp"

namespace slambox {

namespace {
// A = sin(w)/w, B = (1 - cos(w))/w with series near zero.
void SinCosTerms(double w, double& A, double& B) {
  if (std::abs(w) < 1e-6) {
    A = 1.0 - w * w / 6.0;
    B = w / 2.0 - w * w * w / 24.0;
  } else {
    A = std::sin(w) / w;
    B = (1.0 - std::cos(w)) / w;
  }
}
}  // namespace

SE2 Exp(const Eigen::Vector3d& xi) {
  double A, B;
  SinCosTerms(xi.z(), A, B);
  // t = V v with V = [[A, -B], [B, A]]
  return {A * xi.x() - B * xi.y(), B * xi.x() + A * xi.y(), xi.z()};
}

Eigen::Vector3d Log(const SE2& T) {
  double A, B;
  SinCosTerms(T.theta, A, B);
  const double det = A * A + B * B;
  // v = V^-1 t, V^-1 = [[A, B], [-B, A]] / det
  return {(A * T.x + B * T.y) / det, (-B * T.x + A * T.y) / det, T.theta};
}

ComposeJacobians ComposeJacobian(const SE2& A, const SE2& B) {
  // C.t = A.t + R_A B.t, C.theta = A.theta + B.theta; d(R_A B.t)/dA.theta = R_A [-b_y, b_x].
  const Eigen::Matrix2d R = A.rotation();
  ComposeJacobians J{Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Identity()};
  J.J_a.block<2, 1>(0, 2) = R * Eigen::Vector2d(-B.y, B.x);
  J.J_b.topLeftCorner<2, 2>() = R;
  return J;
}

Eigen::Matrix3d ComposeCovariance(const SE2& A, const Eigen::Matrix3d& cov_a, const SE2& B,
                                  const Eigen::Matrix3d& cov_b) {
  const ComposeJacobians J = ComposeJacobian(A, B);
  return J.J_a * cov_a * J.J_a.transpose() + J.J_b * cov_b * J.J_b.transpose();
}

Eigen::Matrix3d Adjoint(const SE2& T) {
  Eigen::Matrix3d Ad = Eigen::Matrix3d::Identity();
  Ad.topLeftCorner<2, 2>() = T.rotation();
  Ad(0, 2) = T.y;
  Ad(1, 2) = -T.x;
  return Ad;
}

}  // namespace slambox
