#include "slam/icp_closed_form.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace slambox {

SE2 AlignPointToPoint(std::span<const Eigen::Vector2d> source, std::span<const Eigen::Vector2d> target,
                      std::span<const double> weights) {
  double w_sum = 0;
  Eigen::Vector2d mu_s = Eigen::Vector2d::Zero(), mu_t = Eigen::Vector2d::Zero();
  for (size_t i = 0; i < source.size(); ++i) {
    w_sum += weights[i];
    mu_s += weights[i] * source[i];
    mu_t += weights[i] * target[i];
  }
  if (w_sum <= 0) return SE2();
  mu_s /= w_sum;
  mu_t /= w_sum;
  Eigen::Matrix2d H = Eigen::Matrix2d::Zero();
  for (size_t i = 0; i < source.size(); ++i) H += weights[i] * (source[i] - mu_s) * (target[i] - mu_t).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix2d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix2d D = Eigen::Matrix2d::Identity();
  D(1, 1) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1.0 : 1.0;  // no reflection
  const Eigen::Matrix2d R = svd.matrixV() * D * svd.matrixU().transpose();
  const Eigen::Vector2d t = mu_t - R * mu_s;
  return {t.x(), t.y(), std::atan2(R(1, 0), R(0, 0))};
}

PointToLineSums AccumulatePointToLine(std::span<const Eigen::Vector2d> source, std::span<const Eigen::Vector2d> target,
                                      std::span<const Eigen::Vector2d> normals, std::span<const double> weights) {
  // Residual e_i = a_i^T t + b_i^T r - d_i with a = n, b = A(s)^T n, A(s) r = R s, d = n^T q.
  double aa00 = 0, aa01 = 0, aa11 = 0, ab00 = 0, ab01 = 0, ab10 = 0, ab11 = 0, bb00 = 0, bb01 = 0, bb11 = 0;
  double ga0 = 0, ga1 = 0, gb0 = 0, gb1 = 0;
  for (size_t i = 0; i < source.size(); ++i) {
    const double nx = normals[i].x(), ny = normals[i].y(), sx = source[i].x(), sy = source[i].y();
    const double b0 = nx * sx + ny * sy, b1 = -nx * sy + ny * sx;
    const double w = weights[i], d = nx * target[i].x() + ny * target[i].y();
    const double wnx = w * nx, wny = w * ny, wb0 = w * b0, wb1 = w * b1;
    aa00 += wnx * nx, aa01 += wnx * ny, aa11 += wny * ny;
    ab00 += wnx * b0, ab01 += wnx * b1, ab10 += wny * b0, ab11 += wny * b1;
    bb00 += wb0 * b0, bb01 += wb0 * b1, bb11 += wb1 * b1;
    ga0 += wnx * d, ga1 += wny * d, gb0 += wb0 * d, gb1 += wb1 * d;
  }
  PointToLineSums s;
  s.Saa << aa00, aa01, aa01, aa11;
  s.Sab << ab00, ab01, ab10, ab11;
  s.Sbb << bb00, bb01, bb01, bb11;
  s.ga << ga0, ga1;
  s.gb << gb0, gb1;
  return s;
}

Eigen::Matrix3d PointToLineHessian(const PointToLineSums& s, double theta_rad) {
  const Eigen::Vector2d r_perp(-std::sin(theta_rad), std::cos(theta_rad));
  Eigen::Matrix3d H;
  H.topLeftCorner<2, 2>() = s.Saa;
  H.topRightCorner<2, 1>() = s.Sab * r_perp;
  H.bottomLeftCorner<1, 2>() = (s.Sab * r_perp).transpose();
  H(2, 2) = r_perp.dot(s.Sbb * r_perp);
  return H;
}

SE2 AlignPointToLine(std::span<const Eigen::Vector2d> source, std::span<const Eigen::Vector2d> target,
                     std::span<const Eigen::Vector2d> normals, std::span<const double> weights,
                     const SE2& T_current) {
  return SolvePointToLine(AccumulatePointToLine(source, target, normals, weights), T_current);
}

SE2 SolvePointToLine(const PointToLineSums& sums, const SE2& T_current) {
  const Eigen::Matrix2d& Saa = sums.Saa;
  const Eigen::Matrix2d& Sab = sums.Sab;
  const Eigen::Matrix2d& Sbb = sums.Sbb;
  const Eigen::Vector2d& ga = sums.ga;
  const Eigen::Vector2d& gb = sums.gb;
  // Pseudo-inverse of Saa: unconstrained translation directions stay where they are.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> ea(Saa);
  const double floor = 1e-9 * std::max(Saa.trace(), 1e-300);
  Eigen::Matrix2d Saa_pinv = Eigen::Matrix2d::Zero(), null_proj = Eigen::Matrix2d::Zero();
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector2d v = ea.eigenvectors().col(k);
    if (ea.eigenvalues()(k) > floor) Saa_pinv += v * v.transpose() / ea.eigenvalues()(k);
    else null_proj += v * v.transpose();
  }
  // t(r) = Saa^+ (ga - Sab r) + P_null t_current; substituting gives r^T Q r - 2 h^T r + const.
  const Eigen::Matrix2d Q = Sbb - Sab.transpose() * Saa_pinv * Sab;
  const Eigen::Vector2d h = gb - Sab.transpose() * Saa_pinv * ga;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eq(Q);
  const Eigen::Vector2d mu = eq.eigenvalues();  // ascending
  const Eigen::Vector2d h_e = eq.eigenvectors().transpose() * h;
  Eigen::Vector2d r(std::cos(T_current.theta), std::sin(T_current.theta));
  const double h_norm = h_e.norm();
  if (h_norm > 1e-12 * std::max(1.0, std::abs(mu(1)))) {
    // Secular equation in u = mu_0 - lambda > 0: phi(u) = h0^2/u^2 + h1^2/(u + gap)^2 - 1 = 0,
    // convex and decreasing, root in (0, |h|]. phi(|h0|) >= 0, so Newton from u = |h0|
    // approaches the root monotonically from the left.
    const double gap = mu(1) - mu(0), h0 = h_e(0) * h_e(0), h1 = h_e(1) * h_e(1);
    double u = std::max(std::abs(h_e(0)), 1e-12 * h_norm);
    for (int it = 0; it < 60; ++it) {
      const double a = 1.0 / u, b = 1.0 / (u + gap);
      const double phi = h0 * a * a + h1 * b * b - 1.0;
      const double dphi = -2.0 * (h0 * a * a * a + h1 * b * b * b);
      const double step = -phi / dphi;
      u += step;
      if (std::abs(step) <= 1e-15 * u) break;
    }
    const Eigen::Vector2d r_e(h_e(0) / u, h_e(1) / (u + mu(1) - mu(0)));
    r = (eq.eigenvectors() * r_e).normalized();
  }
  const Eigen::Vector2d t = Saa_pinv * (ga - Sab * r) + null_proj * T_current.translation();
  return {t.x(), t.y(), std::atan2(r.y(), r.x())};
}

}  // namespace slambox
