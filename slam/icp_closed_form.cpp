#include "slam/icp_closed_form.hpp"

#include <Eigen/Dense>
#include <cmath>

namespace slambox {

SE2 AlignPointToPoint(const std::vector<Eigen::Vector2d>& source, const std::vector<Eigen::Vector2d>& target,
                      const std::vector<double>& weights) {
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

SE2 AlignPointToLine(const std::vector<Eigen::Vector2d>& source, const std::vector<Eigen::Vector2d>& target,
                     const std::vector<Eigen::Vector2d>& normals, const std::vector<double>& weights,
                     const SE2& T_current) {
  // Residual e_i = a_i^T t + b_i^T r - d_i with a = n, b = A(s)^T n, A(s) r = R s, d = n^T q.
  Eigen::Matrix2d Saa = Eigen::Matrix2d::Zero(), Sab = Eigen::Matrix2d::Zero(), Sbb = Eigen::Matrix2d::Zero();
  Eigen::Vector2d ga = Eigen::Vector2d::Zero(), gb = Eigen::Vector2d::Zero();
  for (size_t i = 0; i < source.size(); ++i) {
    const Eigen::Vector2d& n = normals[i];
    const Eigen::Vector2d& s = source[i];
    const Eigen::Vector2d a = n;
    const Eigen::Vector2d b(n.x() * s.x() + n.y() * s.y(), -n.x() * s.y() + n.y() * s.x());
    const double d = n.dot(target[i]);
    const double w = weights[i];
    Saa += w * a * a.transpose();
    Sab += w * a * b.transpose();
    Sbb += w * b * b.transpose();
    ga += w * d * a;
    gb += w * d * b;
  }
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
