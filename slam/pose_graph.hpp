#pragma once
// 2D pose graph, optionally with point landmarks, and its joint solution with Ceres (x, y
// and yaw; yaw on an angle manifold; the anchor pose held constant). Errors, g2o's convention:
//   pose edge      e = [R_i^T (t_j - t_i) - t_ij ; wrap(theta_j - theta_i - theta_ij)],
//   landmark edge  e = R_i^T (l_j - t_i) - z_ij   (slam/landmark_edge_cost.hpp),
//   chi2 = sum over both kinds of e^T Omega e.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/params.hpp"
#include "core/se2.hpp"

namespace slambox {

struct PoseGraphEdge {
  int from = 0;
  int to = 0;
  SE2 T_from_to;  ///< measured pose of `to` in `from`'s frame
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();  ///< over (dx [m], dy [m], dtheta [rad])
  bool loop_closure = false;  ///< the robust kernel applies to loop-closure edges only
};

/// A point landmark observed from a pose (g2o EDGE_SE2_XY, iSAM LANDMARK). No robust kernel.
struct LandmarkEdge {
  int pose = 0;      ///< index into PoseGraph::poses
  int landmark = 0;  ///< index into PoseGraph::landmarks
  Eigen::Vector2d p_pose_landmark = Eigen::Vector2d::Zero();  ///< [m] measured, in the pose's frame
  Eigen::Matrix2d information = Eigen::Matrix2d::Identity();  ///< over (x [m], y [m])
};

struct PoseGraph {
  std::vector<SE2> poses;  ///< T_world_node, the initial guess on input, the solution on output
  std::vector<PoseGraphEdge> edges;
  int anchor = 0;  ///< the pose held fixed (gauge)
  std::vector<Eigen::Vector2d> landmarks;  ///< [m] p_world_landmark, guess on input, solution on output
  std::vector<LandmarkEdge> landmark_edges;
};

enum class RobustKernel { kNone, kHuber, kCauchy, kDcs };
/// none, huber, cauchy, dcs (for `--set` and file options).
const EnumNames<RobustKernel>& RobustKernelNames();

struct PoseGraphSolveOptions {
  RobustKernel loop_kernel = RobustKernel::kNone;
  double kernel_scale = 1.0;  ///< Huber/Cauchy scale on the whitened residual; DCS's Phi
  int max_iterations = 100;
  int num_threads = 1;
  /// Also compute every pose's marginal covariance at the solution (selected inversion of
  /// the sparse Cholesky factor of J^T J, slam/sparse_marginals.hpp; the robust kernels'
  /// weights included). Costs about one more linear solve.
  bool compute_marginals = false;
};

struct PoseGraphSolveResult {
  double chi2_initial = 0.0;  ///< at the input poses, no robust kernel
  double chi2_final = 0.0;    ///< at the solution, no robust kernel
  /// The objective minimized, at the solution: rho(e^T Omega e) summed over loop closures,
  /// e^T Omega e over the rest (= chi2_final without a kernel).
  double robust_chi2_final = 0.0;
  int iterations = 0;          ///< Levenberg-Marquardt steps taken (successful + rejected)
  double time_s = 0.0;         ///< [s] wall time of SolvePoseGraph (problem set-up + solve)
  std::string termination;  ///< Ceres' termination type ("CONVERGENCE", "NO_CONVERGENCE", ...)
  bool usable = false;      ///< Ceres' Summary::IsSolutionUsable()
  /// Per edge: the weight the robust kernel gave it at the solution, rho'(e^T Omega e)
  /// (the IRLS weight on its chi2; DCS: k^2; 1 = full trust, ~0 = rejected; 1 for
  /// odometry edges and without a kernel).
  std::vector<double> edge_weights;
  /// With compute_marginals: per pose, its 3x3 marginal covariance over (x, y, theta)
  /// given all edges, the anchor held fixed (zero for the anchor and unconnected poses).
  /// Empty when not requested or when J^T J is not positive definite (rank-deficient).
  /// With landmarks these are still marginals: the landmarks are variables of the same
  /// J^T J (not held constant), so they are integrated out.
  std::vector<Eigen::Matrix3d> marginal_covariances;
  /// With compute_marginals: per landmark, its 2x2 marginal covariance (zero for a landmark
  /// no edge observes); empty as above.
  std::vector<Eigen::Matrix2d> landmark_marginal_covariances;
};

/// The edge error e above for poses T_i, T_j and measurement T_ij.
Eigen::Vector3d EdgeError(const SE2& T_i, const SE2& T_j, const SE2& T_ij);
/// Sum of e^T Omega e over pose and landmark edges (edges naming missing nodes skipped).
double Chi2(const PoseGraph& graph);

/// Solves poses and landmarks jointly, in place. Throws InputError for an edge naming a
/// missing pose or landmark or a non-positive-definite information matrix.
PoseGraphSolveResult SolvePoseGraph(PoseGraph& graph, const PoseGraphSolveOptions& options = {});

}  // namespace slambox
