#include "slam/icp.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "slam/icp_closed_form.hpp"

namespace slambox {

IcpMetric ParseIcpMetric(const std::string& name) {
  if (name == "point-to-point") return IcpMetric::kPointToPoint;
  if (name == "point-to-line") return IcpMetric::kPointToLine;
  throw InputError("icp metric", 0, "unknown metric '" + name + "'", "use point-to-point or point-to-line");
}
IcpCorrespondence ParseIcpCorrespondence(const std::string& name) {
  if (name == "kdtree") return IcpCorrespondence::kKdTree;
  if (name == "projection") return IcpCorrespondence::kProjection;
  throw InputError("icp correspondence", 0, "unknown correspondence '" + name + "'", "use kdtree or projection");
}
IcpRobustKernel ParseIcpRobustKernel(const std::string& name) {
  if (name == "none") return IcpRobustKernel::kNone;
  if (name == "huber") return IcpRobustKernel::kHuber;
  if (name == "geman-mcclure") return IcpRobustKernel::kGemanMcClure;
  throw InputError("icp robust kernel", 0, "unknown kernel '" + name + "'", "use none, huber or geman-mcclure");
}

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

struct Pairs {
  std::vector<Eigen::Vector2d> transformed;  // scratch: every source point in the target frame
  std::vector<double> beam;                  // scratch: its bearing [rad]
  std::vector<Eigen::Vector2d> source, target, normal;
  std::vector<double> residual, weight;
  void clear() {
    source.clear(), target.clear(), normal.clear(), residual.clear(), weight.clear();
  }
};

void FindPairs(const std::vector<Eigen::Vector2d>& source, const IcpTarget& target, const SE2& T,
               const IcpConfig& config, Pairs& pairs) {
  pairs.clear();
  const Eigen::Matrix2d R = T.rotation();
  const Eigen::Vector2d t = T.translation();
  const double gate2 = config.max_correspondence_m * config.max_correspondence_m;
  const bool p2l = config.metric == IcpMetric::kPointToLine;
  const bool projection = config.correspondence == IcpCorrespondence::kProjection;
  // Projection: transform and find every bearing first, in loops the compiler vectorizes.
  std::vector<Eigen::Vector2d>& q_all = pairs.transformed;
  std::vector<double>& beam_all = pairs.beam;
  q_all.resize(source.size());
  for (size_t i = 0; i < source.size(); ++i) q_all[i] = R * source[i] + t;
  if (projection) {
    beam_all.resize(source.size());
    for (size_t i = 0; i < source.size(); ++i) beam_all[i] = FastAtan2(q_all[i].y(), q_all[i].x());
  }
  for (size_t i = 0; i < source.size(); ++i) {
    const Eigen::Vector2d& p = source[i];
    const Eigen::Vector2d& q = q_all[i];
    int j = -1;
    double d2 = 0;
    const bool found = projection ? NearestOnBeams(target, q, beam_all[i], config.projection_window_beams, &j, &d2)
                                  : NearestByKdTree(target, q, &j, &d2);
    if (!found || d2 > gate2) continue;
    const Eigen::Vector2d& n = target.normals[static_cast<size_t>(j)];
    if (p2l && n.squaredNorm() == 0.0) continue;
    pairs.source.push_back(p);
    pairs.target.push_back(target.points[static_cast<size_t>(j)]);
    pairs.normal.push_back(n);
    pairs.residual.push_back(p2l ? n.dot(q - pairs.target.back()) : std::sqrt(d2));
  }
  if (config.trim_fraction > 0 && pairs.residual.size() > 3) {  // keep the best (1 - trim) fraction
    std::vector<double> mags(pairs.residual.size());
    for (size_t i = 0; i < mags.size(); ++i) mags[i] = std::abs(pairs.residual[i]);
    const size_t keep = std::max<size_t>(3, static_cast<size_t>((1.0 - config.trim_fraction) * mags.size()));
    std::nth_element(mags.begin(), mags.begin() + static_cast<long>(keep - 1), mags.end());
    const double cut = mags[keep - 1];
    size_t w = 0;
    for (size_t i = 0; i < pairs.residual.size() && w < keep; ++i) {
      if (std::abs(pairs.residual[i]) > cut) continue;
      pairs.source[w] = pairs.source[i], pairs.target[w] = pairs.target[i], pairs.normal[w] = pairs.normal[i];
      pairs.residual[w++] = pairs.residual[i];
    }
    pairs.source.resize(w), pairs.target.resize(w), pairs.normal.resize(w), pairs.residual.resize(w);
  }
  pairs.weight.resize(pairs.residual.size());
  for (size_t i = 0; i < pairs.residual.size(); ++i)
    pairs.weight[i] = RobustWeight(config.robust_kernel, pairs.residual[i], config.robust_scale_m);
}

}  // namespace

IcpResult RegisterIcp(const std::vector<Eigen::Vector2d>& source, const IcpTarget& target, const SE2& guess,
                      const IcpConfig& config) {
  IcpResult result;
  result.T_target_source = guess;
  result.num_source = static_cast<int>(source.size());
  Pairs pairs;
  const size_t cap = source.size();
  pairs.source.reserve(cap), pairs.target.reserve(cap), pairs.normal.reserve(cap), pairs.residual.reserve(cap);
  SE2 T = guess;
  Eigen::Matrix3d degenerate_mask = Eigen::Matrix3d::Zero();  // V_d V_d^T of the last iteration
  for (int it = 0; it < config.max_iterations; ++it) {
    FindPairs(source, target, T, config, pairs);
    result.iterations = it + 1;
    result.num_inliers = static_cast<int>(pairs.source.size());
    if (result.num_inliers < std::max(config.min_inliers, 3)) {
      result.converged = false;
      return result;
    }
    // Zero normals (point-to-point pairs off a surface) add nothing to these sums.
    const PointToLineSums sums = AccumulatePointToLine(pairs.source, pairs.target, pairs.normal, pairs.weight);
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
    for (double e : pairs.residual) sum_e2 += e * e;
    result.rms_residual_m = std::sqrt(sum_e2 / result.num_inliers);

    const SE2 T_new = config.metric == IcpMetric::kPointToPoint
                          ? AlignPointToPoint(pairs.source, pairs.target, pairs.weight)
                          : SolvePointToLine(sums, T);
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
  // Covariance sigma^2 H^-1 with sigma^2 from the residuals (N - 3 degrees of freedom).
  const int n = result.num_inliers;
  const double sigma2 = config.sigma_residual_m > 0 ? config.sigma_residual_m * config.sigma_residual_m
                                                    : result.rms_residual_m * result.rms_residual_m *
                                                          n / std::max(1, n - 3);
  // A degenerate direction's small eigenvalue is mostly normal noise, not information:
  // give it the floor so its variance is huge rather than falsely centimetric.
  const double floor = 1e-9 * std::max(1, n);
  const double degenerate_below = config.degeneracy_eigenvalue_ratio * n;
  result.covariance.setZero();
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d v = result.eigenvectors.col(k);
    const double lambda = result.eigenvalues(k) < degenerate_below ? floor : std::max(result.eigenvalues(k), floor);
    result.covariance += v * v.transpose() * sigma2 / lambda;
  }
  return result;
}

}  // namespace slambox
