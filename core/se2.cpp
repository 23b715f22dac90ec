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

Eigen::Matrix3d Adjoint(const SE2& T) {
  Eigen::Matrix3d Ad = Eigen::Matrix3d::Identity();
  Ad.topLeftCorner<2, 2>() = T.rotation();
  Ad(0, 2) = T.y;
  Ad(1, 2) = -T.x;
  return Ad;
}

}  // namespace slambox
