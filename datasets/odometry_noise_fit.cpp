#include "datasets/odometry_noise_fit.hpp"

#include <Eigen/Dense>
#include <cassert>
#include <cmath>
#include <limits>

#include "core/odometry_model.hpp"

namespace slambox {

namespace {
// d(J M J^T) / d(alpha_k) for one increment: J M_k J^T with M_k the k-th term's pattern.
std::array<Eigen::Matrix3d, 4> Basis(const SE2& delta) {
  const OdometryIncrement u = Decompose(delta);
  const MotionPrediction p = PredictMotion(SE2(), u);
  std::array<Eigen::Matrix3d, 4> out;
  for (int k = 0; k < 4; ++k) {
    std::array<double, 4> a{};
    a[static_cast<size_t>(k)] = 1.0;
    out[static_cast<size_t>(k)] = p.J_pose_increment * IncrementCovariance(u, a) * p.J_pose_increment.transpose();
  }
  return out;
}
constexpr int kEntries[6][2] = {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}};
}  // namespace

OdometryNoiseFit FitOdometryAlpha(const std::vector<SE2>& increments, const std::vector<Eigen::Matrix3d>& covariances) {
  assert(increments.size() == covariances.size());
  Eigen::Matrix4d AtA = Eigen::Matrix4d::Zero();
  Eigen::Vector4d Atb = Eigen::Vector4d::Zero();
  double btb = 0.0;
  for (size_t k = 0; k < increments.size(); ++k) {
    const auto B = Basis(increments[k]);
    for (const auto& e : kEntries) {
      Eigen::Vector4d row;
      for (int a = 0; a < 4; ++a) row(a) = B[static_cast<size_t>(a)](e[0], e[1]);
      const double b = covariances[k](e[0], e[1]);
      AtA += row * row.transpose();
      Atb += row * b;
      btb += b * b;
    }
  }
  OdometryNoiseFit fit;
  const double n = 6.0 * static_cast<double>(increments.size());
  if (n == 0) return fit;
  // Non-negative least squares by enumeration of the 15 active sets (4 unknowns): the
  // feasible unconstrained solution on a support with the smallest residual is optimal.
  double best = std::numeric_limits<double>::infinity();
  for (int mask = 1; mask < 16; ++mask) {
    std::vector<int> idx;
    for (int a = 0; a < 4; ++a)
      if (mask & (1 << a)) idx.push_back(a);
    const int m = static_cast<int>(idx.size());
    Eigen::MatrixXd M(m, m);
    Eigen::VectorXd v(m);
    for (int i = 0; i < m; ++i) {
      v(i) = Atb(idx[i]);
      for (int j = 0; j < m; ++j) M(i, j) = AtA(idx[i], idx[j]);
    }
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(M);
    if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 0)) continue;
    const Eigen::VectorXd x = ldlt.solve(v);
    if (!x.allFinite() || x.minCoeff() < 0) continue;
    Eigen::Vector4d a = Eigen::Vector4d::Zero();
    for (int i = 0; i < m; ++i) a(idx[i]) = x(i);
    const double residual = a.dot(AtA * a) - 2.0 * a.dot(Atb) + btb;
    if (residual < best) {
      best = residual;
      for (int i = 0; i < 4; ++i) fit.alpha[static_cast<size_t>(i)] = a(i);
    }
  }
  if (!std::isfinite(best)) return fit;
  fit.rms_residual = std::sqrt(std::max(0.0, best) / n);
  fit.rms_file = std::sqrt(btb / n);
  return fit;
}

}  // namespace slambox
