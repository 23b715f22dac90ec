#include "eval/consistency.hpp"

#include <Eigen/Cholesky>
#include <cassert>
#include <cmath>
#include <limits>

namespace slambox {

namespace {
template <int N>
double Nees(const Eigen::Matrix<double, N, 1>& e, const Eigen::Matrix<double, N, N>& P) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (!e.allFinite() || !P.allFinite()) return nan;
  if (!P.isApprox(P.transpose(), 1e-9)) return nan;
  const Eigen::LLT<Eigen::Matrix<double, N, N>> llt(P);
  if (llt.info() != Eigen::Success) return nan;  // not positive definite
  return e.dot(llt.solve(e));
}
}  // namespace

double PoseNees(const SE2& gt, const SE2& est, const Eigen::Matrix3d& covariance) {
  const Eigen::Vector3d e(est.x - gt.x, est.y - gt.y, NormalizeAngle(est.theta - gt.theta));
  return Nees<3>(e, covariance);
}

double LandmarkNees(const Eigen::Vector2d& gt, const Eigen::Vector2d& est, const Eigen::Matrix2d& covariance) {
  return Nees<2>(Eigen::Vector2d(est - gt), covariance);
}

double FractionInside(const std::vector<double>& values, const NeesBand& band) {
  int finite = 0, inside = 0;
  for (double v : values) {
    if (!std::isfinite(v)) continue;
    ++finite;
    if (v >= band.lo && v <= band.hi) ++inside;
  }
  return finite == 0 ? std::numeric_limits<double>::quiet_NaN() : static_cast<double>(inside) / finite;
}

AneesResult AneesOverRuns(const std::vector<std::vector<double>>& nees, int dims, double confidence) {
  AneesResult r;
  assert(!nees.empty());
  const size_t steps = nees.front().size();
  r.anees.assign(steps, 0.0);
  for (const auto& run : nees) {
    assert(run.size() == steps);
    for (size_t k = 0; k < steps; ++k) r.anees[k] += run[k];
  }
  for (double& a : r.anees) a /= static_cast<double>(nees.size());
  r.band = AneesBand(dims, static_cast<int>(nees.size()), confidence);
  r.fraction_inside = FractionInside(r.anees, r.band);
  return r;
}

}  // namespace slambox
