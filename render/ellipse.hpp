#pragma once
// Covariance ellipses: the k-sigma contour {p : (p - mu)^T Sigma^-1 (p - mu) = k^2} of a
// 2D Gaussian, traced as mu + k L [cos t, sin t]^T with L L^T = Sigma (Cholesky would do;
// the eigen-decomposition L = V sqrt(Lambda) is used so a singular Sigma still works).
#include <Eigen/Core>
#include <vector>

namespace slambox::render {

/// `segments` points on the k-sigma ellipse (k = 2 encloses 86.5% of a 2D Gaussian).
/// A non-finite or non-PSD covariance yields no points.
std::vector<Eigen::Vector2d> CovarianceEllipse(const Eigen::Vector2d& mean, const Eigen::Matrix2d& covariance,
                                               double k_sigma = 2.0, int segments = 72);

}  // namespace slambox::render
