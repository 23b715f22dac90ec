#include "slam/icp.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <span>

#include "core/error.hpp"
#include "slam/icp_closed_form.hpp"
#include "slam/icp_prior.hpp"

namespace slambox {

double RobustWeight(IcpRobustKernel kernel, double e, double scale) {
  const double a = std::abs(e);
  switch (kernel) {
    case IcpRobustKernel::kHuber:  // rho = e^2/2 inside, k|e| - k^2/2 outside; w = rho'(e)/e
      return a <= scale ? 1.0 : scale / a;
    case IcpRobustKernel::kGemanMcClure: {  // rho = k^2 e^2 / (2 (k^2 + e^2)); w = k^4 / (k^2 + e^2)^2
      const double k2 = scale * scale;
      return k2 * k2 / ((k2 + e * e) * (k2 + e * e));
    }
    case IcpRobustKernel::kNone:
      break;
  }
  return 1.0;
}

namespace {

// Scratch reused by every iteration: sized once per registration, so the loop allocates
// nothing. Pairs live in the first `count` entries.
struct Pairs {
  explicit Pairs(size_t n)
      : transformed(n), bearing(n), dist2(n), nearest(n), source(n), target(n), normal(n), residual(n),
        weight(n), magnitude(n) {}
  std::vector<Eigen::Vector2d> transformed;  // every source point in the target frame
  std::vector<double> bearing;               // its bearing [rad] (projection)
  std::vector<double> dist2;                 // [m^2] to its nearest target point
  std::vector<int> nearest;                  // that point's index, -1 without one
  std::vector<Eigen::Vector2d> source, target, normal;
  std::vector<double> residual, weight, magnitude;
  size_t count = 0;
  std::span<const Eigen::Vector2d> Source() const { return {source.data(), count}; }
  std::span<const Eigen::Vector2d> Target() const { return {target.data(), count}; }
  std::span<const Eigen::Vector2d> Normal() const { return {normal.data(), count}; }
  std::span<const double> Weight() const { return {weight.data(), count}; }
};

void FindPairs(const std::vector<Eigen::Vector2d>& source, const IcpTarget& target, const SE2& T,
               const IcpConfig& config, Pairs& pairs) {
  const Eigen::Matrix2d R = T.rotation();
  const Eigen::Vector2d t = T.translation();
  const double gate2 = config.max_correspondence_m * config.max_correspondence_m;
  const bool p2l = config.metric == IcpMetric::kPointToLine;
  const bool projection = config.correspondence == IcpCorrespondence::kProjection;
  const size_t n = source.size();
  // Transform and find every bearing first, in loops the compiler vectorizes.
  Eigen::Vector2d* q_all = pairs.transformed.data();
  for (size_t i = 0; i < n; ++i) q_all[i] = R * source[i] + t;
  if (projection) {
    double* bearing = pairs.bearing.data();
    for (size_t i = 0; i < n; ++i) bearing[i] = FastAtan2(q_all[i].y(), q_all[i].x());
  }
  // Nearest target point of every source point, then the pairs: two loops, so that the
  // first has no data-dependent branch and consecutive searches overlap.
  int* nearest = pairs.nearest.data();
  double* dist2 = pairs.dist2.data();
  if (projection) {
    NearestOnBeamsBatch(target, q_all, pairs.bearing.data(), n, config.projection_window_beams, nearest, dist2);
  } else {
    for (size_t i = 0; i < n; ++i)
      if (!NearestByKdTree(target, q_all[i], &nearest[i], &dist2[i])) nearest[i] = -1;
  }
  size_t k = 0;
  for (size_t i = 0; i < n; ++i) {
    const int j = nearest[i];
    if (j < 0 || dist2[i] > gate2) continue;
    const Eigen::Vector2d& nrm = target.normals[static_cast<size_t>(j)];
    if (p2l && nrm.squaredNorm() == 0.0) continue;
    const Eigen::Vector2d& tp = target.points[static_cast<size_t>(j)];
    pairs.source[k] = source[i];
    pairs.target[k] = tp;
    pairs.normal[k] = nrm;
    pairs.residual[k] = p2l ? nrm.dot(q_all[i] - tp) : std::sqrt(dist2[i]);
    ++k;
  }
  pairs.count = k;
  if (config.trim_fraction > 0 && k > 3) {  // keep the best (1 - trim) fraction
    double* mags = pairs.magnitude.data();
    for (size_t i = 0; i < k; ++i) mags[i] = std::abs(pairs.residual[i]);
    const size_t keep = std::max<size_t>(3, static_cast<size_t>((1.0 - config.trim_fraction) * k));
    std::nth_element(mags, mags + static_cast<long>(keep - 1), mags + k);
    const double cut = mags[keep - 1];
    size_t w = 0;
    for (size_t i = 0; i < k && w < keep; ++i) {
      if (std::abs(pairs.residual[i]) > cut) continue;
      pairs.source[w] = pairs.source[i], pairs.target[w] = pairs.target[i], pairs.normal[w] = pairs.normal[i];
      pairs.residual[w++] = pairs.residual[i];
    }
    pairs.count = w;
  }
  for (size_t i = 0; i < pairs.count; ++i)
    pairs.weight[i] = RobustWeight(config.robust_kernel, pairs.residual[i], config.robust_scale_m);
}

// Residual variance sigma^2 (from the RMS with N - 3 degrees of freedom unless configured)
// and the eigenvalues of H / sigma^2 (the scan's information), a degenerate direction's
// given the floor: its small eigenvalue is mostly normal noise, not information, so its
// variance is huge rather than falsely centimetric.
struct ScanInformation {
  double sigma2 = 0.0;
  Eigen::Vector3d eigenvalues = Eigen::Vector3d::Zero();
};
ScanInformation ScanInformationOf(const IcpResult& r, const IcpConfig& config) {
  const int n = r.num_inliers;
  ScanInformation s;
  s.sigma2 = config.sigma_residual_m > 0 ? config.sigma_residual_m * config.sigma_residual_m
                                         : r.rms_residual_m * r.rms_residual_m * n / std::max(1, n - 3);
  const double floor = 1e-9 * std::max(1, n);
  const double degenerate_below = config.degeneracy_eigenvalue_ratio * n;
  for (int k = 0; k < 3; ++k)
    s.eigenvalues(k) = r.eigenvalues(k) < degenerate_below ? floor : std::max(r.eigenvalues(k), floor);
  return s;
}

}  // namespace

IcpResult RegisterIcp(const std::vector<Eigen::Vector2d>& source, const IcpTarget& target, const SE2& guess,
                      const IcpConfig& config, const IcpPrior* prior) {
  IcpResult result;
  result.T_target_source = guess;
  result.num_source = static_cast<int>(source.size());
  Pairs pairs(source.size());
  SE2 T = guess;
  Eigen::Matrix3d degenerate_mask = Eigen::Matrix3d::Zero();  // V_d V_d^T of the last iteration
  for (int it = 0; it < config.max_iterations; ++it) {
    FindPairs(source, target, T, config, pairs);
    result.iterations = it + 1;
    result.num_inliers = static_cast<int>(pairs.count);
    if (result.num_inliers < std::max(config.min_inliers, 3)) {
      result.converged = false;
      return result;
    }
    // Zero normals (point-to-point pairs off a surface) add nothing to these sums.
    const PointToLineSums sums = AccumulatePointToLine(pairs.Source(), pairs.Target(), pairs.Normal(), pairs.Weight());
    result.hessian = PointToLineHessian(sums, T.theta);
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
    eig.computeDirect(result.hessian);
    result.eigenvalues = eig.eigenvalues();
    result.eigenvectors = eig.eigenvectors();
    result.degenerate_dimensions = 0;
    degenerate_mask.setZero();
    for (int k = 0; k < 3; ++k) {
      if (result.eigenvalues(k) < config.degeneracy_eigenvalue_ratio * result.num_inliers) {
        ++result.degenerate_dimensions;
        degenerate_mask += result.eigenvectors.col(k) * result.eigenvectors.col(k).transpose();
      }
    }
    double sum_e2 = 0;
    for (size_t i = 0; i < pairs.count; ++i) sum_e2 += pairs.residual[i] * pairs.residual[i];
    result.rms_residual_m = std::sqrt(sum_e2 / result.num_inliers);

    SE2 T_new = config.metric == IcpMetric::kPointToPoint
                          ? AlignPointToPoint(pairs.Source(), pairs.Target(), pairs.Weight())
                          : SolvePointToLine(sums, T);
    if (prior) {  // the scan's information H / sigma^2 (degenerate directions floored) against the prior's
      // H sums robust weights, so sigma^2 is the weighted residual variance: outliers the
      // kernel has all but dropped must not inflate it (the unweighted RMS would).
      double sum_w = 0, sum_we2 = 0;
      for (size_t i = 0; i < pairs.count; ++i) {
        sum_w += pairs.weight[i];
        sum_we2 += pairs.weight[i] * pairs.residual[i] * pairs.residual[i];
      }
      IcpConfig weighted = config;
      if (weighted.sigma_residual_m <= 0) weighted.sigma_residual_m = std::sqrt(std::max(sum_we2 / std::max(sum_w, 1e-12), 1e-12));
      const ScanInformation si = ScanInformationOf(result, weighted);
      const Eigen::Matrix3d A = result.eigenvectors * (si.eigenvalues / si.sigma2).asDiagonal() * result.eigenvectors.transpose();
      T_new = FuseWithPrior(T_new, A, *prior);
    }
    Eigen::Vector3d step(T_new.x - T.x, T_new.y - T.y, NormalizeAngle(T_new.theta - T.theta));
    if (config.remap_degenerate) step -= degenerate_mask * step;  // Zhang 2016: no motion along weak directions
    T = SE2(T.x + step.x(), T.y + step.y(), T.theta + step.z());
    if (step.head<2>().norm() < config.convergence_translation_m &&
        std::abs(step.z()) < config.convergence_rotation_rad) {
      result.converged = true;
      break;
    }
  }
  result.T_target_source = T;
  result.degenerate = result.degenerate_dimensions > 0;
  result.degenerate_direction = result.degenerate ? Eigen::Vector3d(result.eigenvectors.col(0)) : Eigen::Vector3d::Zero();
  // Covariance sigma^2 H^-1 over the scan's information (no prior in it).
  const ScanInformation si = ScanInformationOf(result, config);
  result.covariance.setZero();
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d v = result.eigenvectors.col(k);
    result.covariance += v * v.transpose() * si.sigma2 / si.eigenvalues(k);
  }
  return result;
}

}  // namespace slambox
