#include "slam/scan_likelihood.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cassert>
#include <cmath>

#include "slam/data_association.hpp"
#include "slam/range_bearing.hpp"

namespace slambox {

namespace {
double NormalCdf(double x) { return 0.5 * std::erfc(-x / std::sqrt(2.0)); }
/// Beyond this d^2 a landmark's density (below e^-25 of its peak) is left out of the sum.
constexpr double kNegligibleChi2 = 50.0;
}  // namespace

double ProbabilityInView(const Eigen::Vector2d& z, const Eigen::Matrix2d& C, double range_max_m, double half_fov_rad) {
  const double sigma_r = std::sqrt(std::max(C(0, 0), 1e-18)), sigma_b = std::sqrt(std::max(C(1, 1), 1e-18));
  const double in_range = NormalCdf((range_max_m - z.x()) / sigma_r);
  if (half_fov_rad >= M_PI) return in_range;
  const double in_fov = NormalCdf((half_fov_rad - z.y()) / sigma_b) - NormalCdf((-half_fov_rad - z.y()) / sigma_b);
  return in_range * std::clamp(in_fov, 0.0, 1.0);
}

double ScanLogLikelihood(const EkfSlamState& state, const std::vector<Eigen::Vector2d>& z, const Eigen::Matrix2d& R,
                         const std::vector<double>& p_detect, const ScanLikelihoodModel& model) {
  const int n = state.NumLandmarks();
  assert(static_cast<int>(p_detect.size()) == n);
  const SE2 pose = state.Pose();
  std::vector<Eigen::Vector2d> h(n);
  std::vector<Eigen::Matrix2d> S_inv(n);
  std::vector<double> peak(n);  // w_j / (2 pi sqrt(det S_j))
  double log_p = 0.0;
  for (int j = 0; j < n; ++j) {
    h[j] = PredictObservation(pose, state.Landmark(j)).z;
    const Eigen::Matrix2d S = InnovationCovariance(state, j, R);
    S_inv[j] = S.inverse();
    peak[j] = p_detect[j] / (2.0 * M_PI * std::sqrt(S.determinant()));
    log_p -= p_detect[j] * ProbabilityInView(h[j], S - R, model.range_max_m, model.half_fov_rad);
  }
  for (const Eigen::Vector2d& zi : z) {
    double density = model.false_density_per_m2 * zi.x();
    for (int j = 0; j < n; ++j) {
      const Eigen::Vector2d nu = Innovation(zi, h[j]);
      const double d2 = nu.dot(S_inv[j] * nu);
      if (d2 < kNegligibleChi2) density += peak[j] * std::exp(-0.5 * d2);
    }
    log_p += std::log(std::max(density, 1e-300));
  }
  return log_p;
}

}  // namespace slambox
