#pragma once
// ICP scan registration in SE(2), KISS-ICP style: a free function over plain data.
// Finds T_target_source such that target ≈ T_target_source * source.
//   metric:          point-to-point (closed-form SVD step) or point-to-line (Censi's exact
//                    PLICP step), optional IRLS robust weights (Huber, Geman-McClure);
//   correspondences: kd-tree (nanoflann) or projection into the reference scan's beams;
//   outliers:        distance gate, trimmed fraction (the caller passes an adaptive gate,
//                    see slam/adaptive_threshold.hpp, as max_correspondence_m);
//   degeneracy:      Zhang, Kaess & Singh 2016 — Hessian eigen-directions with small
//                    eigenvalues are not moved (solution remapping keeps the guess there).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/se2.hpp"
#include "slam/icp_prior.hpp"
#include "slam/icp_target.hpp"

namespace slambox {

enum class IcpMetric { kPointToPoint, kPointToLine };
enum class IcpCorrespondence { kKdTree, kProjection };
enum class IcpRobustKernel { kNone, kHuber, kGemanMcClure };

struct IcpConfig {
  IcpMetric metric = IcpMetric::kPointToLine;
  IcpCorrespondence correspondence = IcpCorrespondence::kKdTree;
  IcpRobustKernel robust_kernel = IcpRobustKernel::kNone;
  double robust_scale_m = 0.05;              ///< [m] Huber corner / Geman-McClure scale on the residual
  int max_iterations = 30;                   ///< iteration cap
  double convergence_translation_m = 1e-4;   ///< [m] stop when the step moves less than this ...
  double convergence_rotation_rad = 1e-4;    ///< [rad] ... and turns less than this
  double max_correspondence_m = 0.5;         ///< [m] distance gate on nearest-neighbour pairs
  double trim_fraction = 0.0;                ///< [0,1) drop this fraction of the worst pairs
  int projection_window_beams = 1;           ///< beams searched each side of the projected bearing
  int min_inliers = 10;                      ///< fewer pairs: stop, converged = false
  /// Degenerate direction: Hessian eigenvalue / inliers below this [m^2/m^2, rad: m^2].
  double degeneracy_eigenvalue_ratio = 0.03;
  bool remap_degenerate = true;              ///< keep the guess along degenerate directions
  double sigma_residual_m = 0.0;             ///< [m] residual std for the covariance (0 = from RMS)
};
/// Names used by modules' string parameters ("point-to-line", "kdtree", "huber", ...).

struct IcpResult {
  SE2 T_target_source;
  bool converged = false;
  int iterations = 0;
  int num_inliers = 0;          ///< pairs kept at the last iteration
  int num_source = 0;           ///< source points given
  double rms_residual_m = 0.0;  ///< [m] RMS of the metric's residual over inliers
  /// Point-to-line Gauss-Newton Hessian sum w J^T J over (t_x [m], t_y [m], theta [rad])
  /// at the solution (for both metrics; needs target normals).
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();
  Eigen::Vector3d eigenvalues = Eigen::Vector3d::Zero();    ///< of hessian, ascending
  Eigen::Matrix3d eigenvectors = Eigen::Matrix3d::Identity();  ///< columns match eigenvalues
  /// sigma^2 H^-1 (Censi 2007 notes this Hessian-based estimate is optimistic: it ignores
  /// correspondence errors and correlated noise). Degenerate directions get a huge variance.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
  bool degenerate = false;
  int degenerate_dimensions = 0;
  Eigen::Vector3d degenerate_direction = Eigen::Vector3d::Zero();  ///< unit eigenvector of the weakest one
};

/// Registers `source` (its own frame) to `target` starting from the guess (e.g. odometry).
/// With a prior (slam/icp_prior.hpp), each iteration's solution for fixed pairs is fused
/// with it, weighted by the scan's information H / sigma^2; the result's covariance and
/// Hessian stay the scan's own.
IcpResult RegisterIcp(const std::vector<Eigen::Vector2d>& source, const IcpTarget& target,
                      const SE2& T_target_source_guess, const IcpConfig& config,
                      const IcpPrior* prior = nullptr);

/// IRLS weight of a residual e for the kernel (1 at e = 0).
double RobustWeight(IcpRobustKernel kernel, double e, double scale);

}  // namespace slambox
