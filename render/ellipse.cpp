#include "render/ellipse.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace slambox::render {

std::vector<Eigen::Vector2d> CovarianceEllipse(const Eigen::Vector2d& mean, const Eigen::Matrix2d& covariance,
                                               double k_sigma, int segments) {
  if (!covariance.allFinite() || !mean.allFinite()) return {};
  const Eigen::Matrix2d sym = 0.5 * (covariance + covariance.transpose());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(sym);
  if (eig.info() != Eigen::Success || eig.eigenvalues().minCoeff() < -1e-12 * std::max(1.0, sym.norm())) return {};
  const Eigen::Matrix2d L = eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal();
  std::vector<Eigen::Vector2d> pts;
  pts.reserve(segments);
  for (int i = 0; i < segments; ++i) {
    const double t = 2.0 * M_PI * i / segments;
    pts.push_back(mean + k_sigma * L * Eigen::Vector2d(std::cos(t), std::sin(t)));
  }
  return pts;
}

}  // namespace slambox::render
