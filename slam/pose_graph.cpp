// The 2D pose graph error (g2o's convention) and its solution with Ceres: one
// (x, y, yaw) block per pose (Euclidean x, y; yaw on the angle manifold), the anchor
// constant, sparse normal Cholesky, robust kernels on loop-closure edges only.
// One 3-vector block per pose (rather than separate x, y, yaw blocks as in Ceres'
// pose_graph_2d example) gives dense 3x3 blocks in J^T J: fewer, larger blocks, less
// bookkeeping; bench/pose_graph_bench.cpp measures both layouts side by side.
#include "slam/pose_graph.hpp"

#include <ceres/ceres.h>

#include <chrono>
#include <cmath>
#include <memory>

#include "core/error.hpp"
#include "slam/angle_manifold.hpp"
#include "slam/dcs_loss.hpp"
#include "slam/landmark_edge_cost.hpp"
#include "slam/pose_graph_cost.hpp"
#include "slam/sparse_marginals.hpp"

namespace slambox {

Eigen::Vector3d EdgeError(const SE2& T_i, const SE2& T_j, const SE2& T_ij) {
  Eigen::Vector3d e;
  e.head<2>() = T_i.rotation().transpose() * (T_j.translation() - T_i.translation()) - T_ij.translation();
  e.z() = NormalizeAngle(T_j.theta - T_i.theta - T_ij.theta);
  return e;
}

double Chi2(const PoseGraph& graph) {
  const int n = static_cast<int>(graph.poses.size());
  double chi2 = 0.0;
  for (const PoseGraphEdge& edge : graph.edges) {
    if (edge.from < 0 || edge.from >= n || edge.to < 0 || edge.to >= n) continue;
    const Eigen::Vector3d e = EdgeError(graph.poses[edge.from], graph.poses[edge.to], edge.T_from_to);
    chi2 += e.dot(edge.information * e);
  }
  const int m = static_cast<int>(graph.landmarks.size());
  for (const LandmarkEdge& edge : graph.landmark_edges) {
    if (edge.pose < 0 || edge.pose >= n || edge.landmark < 0 || edge.landmark >= m) continue;
    const Eigen::Vector2d e =
        LandmarkEdgeError(graph.poses[edge.pose].vector(), graph.landmarks[edge.landmark], edge.p_pose_landmark);
    chi2 += e.dot(edge.information * e);
  }
  return chi2;
}

const EnumNames<RobustKernel>& RobustKernelNames() {
  static const EnumNames<RobustKernel> names = {{RobustKernel::kNone, "none"},
                                                {RobustKernel::kHuber, "huber"},
                                                {RobustKernel::kCauchy, "cauchy"},
                                                {RobustKernel::kDcs, "dcs"}};
  return names;
}

namespace {

std::unique_ptr<ceres::LossFunction> MakeLoopLoss(RobustKernel kernel, double scale) {
  switch (kernel) {
    case RobustKernel::kNone: return nullptr;
    case RobustKernel::kHuber: return std::make_unique<ceres::HuberLoss>(scale);
    case RobustKernel::kCauchy: return std::make_unique<ceres::CauchyLoss>(scale);
    case RobustKernel::kDcs: return std::make_unique<DcsLoss>(scale);
  }
  return nullptr;
}

// Landmark edges name existing poses and landmarks and have SPD information; landmarks
// are finite. Their whitening factors are returned, as for pose edges.
void ValidateLandmarks(const PoseGraph& graph, std::vector<Eigen::Matrix2d>* sqrt_informations) {
  const int n = static_cast<int>(graph.poses.size());
  const int m = static_cast<int>(graph.landmarks.size());
  for (int j = 0; j < m; ++j)
    if (!graph.landmarks[j].allFinite())
      throw InputError("", 0, "landmark " + std::to_string(j) + " of the initial guess is not finite",
                       "give finite landmark positions (or place them with LandmarksFromObservations)");
  sqrt_informations->resize(graph.landmark_edges.size());
  for (size_t k = 0; k < graph.landmark_edges.size(); ++k) {
    const LandmarkEdge& edge = graph.landmark_edges[k];
    const std::string name = "landmark edge " + std::to_string(k) + " (pose " + std::to_string(edge.pose) +
                             " -> landmark " + std::to_string(edge.landmark) + ")";
    if (edge.pose < 0 || edge.pose >= n)
      throw InputError("", 0, name + " names a missing pose (the graph has " + std::to_string(n) + ")",
                       "connect landmark edges only to poses 0.." + std::to_string(n - 1));
    if (edge.landmark < 0 || edge.landmark >= m)
      throw InputError("", 0, name + " names a missing landmark (the graph has " + std::to_string(m) + ")",
                       "add the landmark to PoseGraph::landmarks");
    if (!edge.p_pose_landmark.allFinite())
      throw InputError("", 0, name + " has a non-finite measurement", "give a finite measured point");
    if (!SqrtInformation(edge.information, &(*sqrt_informations)[k]))
      throw InputError("", 0, name + " has an information matrix that is not symmetric positive definite",
                       "give a symmetric positive definite 2x2 information matrix");
  }
}

void ValidateGraph(const PoseGraph& graph, const PoseGraphSolveOptions& options,
                   std::vector<Eigen::Matrix3d>* sqrt_informations) {
  const int n = static_cast<int>(graph.poses.size());
  if (n == 0) throw InputError("", 0, "the pose graph has no poses", "give at least one pose");
  if (graph.anchor < 0 || graph.anchor >= n)
    throw InputError("", 0, "anchor " + std::to_string(graph.anchor) + " is not a pose index (0.." +
                                std::to_string(n - 1) + ")",
                     "set PoseGraph::anchor to an existing pose");
  if (!(options.kernel_scale > 0.0) || !std::isfinite(options.kernel_scale))
    throw InputError("", 0, "robust kernel scale must be positive", "set kernel_scale > 0");
  if (options.max_iterations < 0 || options.num_threads < 1)
    throw InputError("", 0, "max_iterations must be >= 0 and num_threads >= 1", "fix PoseGraphSolveOptions");
  for (int i = 0; i < n; ++i)
    if (!graph.poses[i].vector().allFinite())
      throw InputError("", 0, "pose " + std::to_string(i) + " of the initial guess is not finite",
                       "give finite initial poses (or initialize with SpanningTreeInitialization)");
  sqrt_informations->resize(graph.edges.size());
  for (size_t k = 0; k < graph.edges.size(); ++k) {
    const PoseGraphEdge& edge = graph.edges[k];
    const std::string name = "edge " + std::to_string(k) + " (" + std::to_string(edge.from) + " -> " +
                             std::to_string(edge.to) + ")";
    if (edge.from < 0 || edge.from >= n || edge.to < 0 || edge.to >= n)
      throw InputError("", 0, name + " names a missing pose (the graph has " + std::to_string(n) + ")",
                       "connect edges only to poses 0.." + std::to_string(n - 1));
    if (edge.from == edge.to)
      throw InputError("", 0, name + " connects a pose to itself", "remove the edge");
    if (!SqrtInformation(edge.information, &(*sqrt_informations)[k]))
      throw InputError("", 0, name + " has an information matrix that is not symmetric positive definite",
                       "give a symmetric positive definite 3x3 information matrix");
  }
}

// Diagonal blocks of the inverse of J^T J at the solution: the marginal covariance of each
// pose (and landmark) under the Gaussian (Laplace) approximation of the posterior, the anchor
// fixed. Every landmark block is a column of J^T J too (after the poses), so the pose blocks
// are marginals over the landmarks, not conditionals given them. Selected inversion of the
// sparse Cholesky factor (slam/sparse_marginals.hpp); false when J^T J is not positive
// definite (a pose or landmark the edges do not determine).
bool MarginalCovariances(ceres::Problem& problem, std::vector<double>& x, std::vector<double>& l, size_t anchor,
                         PoseGraphSolveResult* result) {
  const size_t n = x.size() / 3, m = l.size() / 2;
  result->marginal_covariances.assign(n, Eigen::Matrix3d::Zero());
  if (m > 0) result->landmark_marginal_covariances.assign(m, Eigen::Matrix2d::Zero());
  std::vector<double*> blocks;
  std::vector<size_t> node_of_block;  // pose index, or n + landmark index
  std::vector<std::pair<int, int>> requested;
  int offset = 0;
  for (size_t i = 0; i < n; ++i)
    if (i != anchor && problem.HasParameterBlock(&x[3 * i])) {
      requested.emplace_back(offset, 3);
      offset += 3;
      blocks.push_back(&x[3 * i]);
      node_of_block.push_back(i);
    }
  for (size_t j = 0; j < m; ++j)
    if (problem.HasParameterBlock(&l[2 * j])) {
      requested.emplace_back(offset, 2);
      offset += 2;
      blocks.push_back(&l[2 * j]);
      node_of_block.push_back(n + j);
    }
  if (blocks.empty()) return true;
  const DiagonalBlocksOfInverse inverse = InverseDiagonalBlocks(InformationMatrix(problem, blocks), requested);
  if (!inverse.ok) return false;
  for (size_t b = 0; b < blocks.size(); ++b) {
    if (node_of_block[b] < n)
      result->marginal_covariances[node_of_block[b]] = inverse.blocks[b];
    else
      result->landmark_marginal_covariances[node_of_block[b] - n] = inverse.blocks[b];
  }
  return true;
}

}  // namespace

PoseGraphSolveResult SolvePoseGraph(PoseGraph& graph, const PoseGraphSolveOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<Eigen::Matrix3d> sqrt_informations;
  ValidateGraph(graph, options, &sqrt_informations);
  std::vector<Eigen::Matrix2d> landmark_sqrt_informations;
  ValidateLandmarks(graph, &landmark_sqrt_informations);

  PoseGraphSolveResult result;
  result.chi2_initial = Chi2(graph);

  // Parameters: one (x, y, theta) block per pose, copied out of the SE2s and back.
  const size_t n = graph.poses.size();
  std::vector<double> x(3 * n);
  for (size_t i = 0; i < n; ++i) {
    x[3 * i] = graph.poses[i].x;
    x[3 * i + 1] = graph.poses[i].y;
    x[3 * i + 2] = graph.poses[i].theta;
  }
  const size_t m = graph.landmarks.size();  // one (x, y) block per landmark, after the poses
  std::vector<double> l(2 * m);
  for (size_t j = 0; j < m; ++j) {
    l[2 * j] = graph.landmarks[j].x();
    l[2 * j + 1] = graph.landmarks[j].y();
  }

  std::unique_ptr<ceres::LossFunction> loop_loss = MakeLoopLoss(options.loop_kernel, options.kernel_scale);
  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  PoseManifold pose_manifold;
  for (size_t k = 0; k < graph.edges.size(); ++k) {
    const PoseGraphEdge& edge = graph.edges[k];
    const size_t i = edge.from, j = edge.to;
    ceres::LossFunction* loss = edge.loop_closure ? loop_loss.get() : nullptr;
    problem.AddResidualBlock(new PoseGraphEdgeCost(edge.T_from_to, sqrt_informations[k]), loss, &x[3 * i],
                             &x[3 * j]);
  }
  for (size_t k = 0; k < graph.landmark_edges.size(); ++k) {
    const LandmarkEdge& edge = graph.landmark_edges[k];
    problem.AddResidualBlock(new LandmarkEdgeCost(edge.p_pose_landmark, landmark_sqrt_informations[k]), nullptr,
                             &x[3 * static_cast<size_t>(edge.pose)], &l[2 * static_cast<size_t>(edge.landmark)]);
  }
  for (size_t i = 0; i < n; ++i)
    if (problem.HasParameterBlock(&x[3 * i])) problem.SetManifold(&x[3 * i], &pose_manifold);
  const size_t a = graph.anchor;
  if (problem.HasParameterBlock(&x[3 * a])) problem.SetParameterBlockConstant(&x[3 * a]);

  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver_options.max_num_iterations = options.max_iterations;
  solver_options.num_threads = options.num_threads;
  solver_options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  if (problem.NumResidualBlocks() > 0) {
    ceres::Solve(solver_options, &problem, &summary);
    result.iterations = static_cast<int>(summary.iterations.size()) - 1;  // entry 0 is the start
    result.termination = ceres::TerminationTypeToString(summary.termination_type);
    result.usable = summary.IsSolutionUsable();
  } else {
    result.termination = "CONVERGENCE";
    result.usable = true;
  }

  if (result.usable) {
    for (size_t i = 0; i < n; ++i) graph.poses[i] = SE2(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
    for (size_t j = 0; j < m; ++j) graph.landmarks[j] = Eigen::Vector2d(l[2 * j], l[2 * j + 1]);
  }
  result.chi2_final = Chi2(graph);

  // IRLS weight rho'(chi2_edge) at the solution: 1 for a trusted edge, ~0 for a rejected one.
  result.edge_weights.assign(graph.edges.size(), 1.0);
  result.robust_chi2_final = result.chi2_final;
  if (loop_loss) {
    for (size_t k = 0; k < graph.edges.size(); ++k) {
      const PoseGraphEdge& edge = graph.edges[k];
      if (!edge.loop_closure) continue;
      const Eigen::Vector3d e = EdgeError(graph.poses[edge.from], graph.poses[edge.to], edge.T_from_to);
      const double chi2 = e.dot(edge.information * e);
      double rho[3];
      loop_loss->Evaluate(chi2, rho);
      result.edge_weights[k] = rho[1];
      result.robust_chi2_final += rho[0] - chi2;
    }
  }
  if (options.compute_marginals && result.usable && !MarginalCovariances(problem, x, l, a, &result)) {
    result.marginal_covariances.clear();
    result.landmark_marginal_covariances.clear();
  }
  result.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace slambox
