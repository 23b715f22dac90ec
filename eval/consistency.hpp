#pragma once
// Filter consistency (Bar-Shalom, Li, Kirubarajan 2001, Sec. 5.4.2): the normalized
// estimation error squared NEES = e^T P^-1 e of a consistent estimator is chi^2 with
// d = dim(e) degrees of freedom, mean d. For poses e = (x_est - x_gt, y_est - y_gt,
// wrap(theta_est - theta_gt)); for landmarks the 2x2 position block.
#include <Eigen/Core>
#include <vector>

#include "core/se2.hpp"
#include "core/chi_square.hpp"

namespace slambox {

/// NaN when the covariance is not symmetric positive definite or anything is non-finite.
double PoseNees(const SE2& gt, const SE2& est, const Eigen::Matrix3d& covariance);
double LandmarkNees(const Eigen::Vector2d& gt, const Eigen::Vector2d& est, const Eigen::Matrix2d& covariance);

/// ANEES over N Monte Carlo runs at each step: mean over runs of nees[run][step] (all
/// runs the same length), the band for (dims, N) and the fraction of steps inside it.
struct AneesResult {
  std::vector<double> anees;  ///< per step
  NeesBand band;
  double fraction_inside = 0.0;
};
AneesResult AneesOverRuns(const std::vector<std::vector<double>>& nees_per_run, int dims, double confidence = 0.95);

/// Fraction of finite values inside [band.lo, band.hi]; NaN when none is finite.
double FractionInside(const std::vector<double>& values, const NeesBand& band);

}  // namespace slambox
