#include "slam/landmark_graph.hpp"

#include <ceres/ceres.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "slam/angle_manifold.hpp"
#include "slam/pose_graph_cost.hpp"
#include "slam/sparse_marginals.hpp"

namespace slambox {

Eigen::Matrix3d FactorCovariance(const OdometryConstraint& odometry) {
  return odometry.covariance + Eigen::Vector3d(1e-8, 1e-8, 1e-8).asDiagonal().toDenseMatrix();
}

namespace {

struct RangeBearingFactor {
  RangeBearingFactor(const Eigen::Vector2d& z, const Eigen::Matrix2d& sqrt_information)
      : z_(z), sqrt_information_(sqrt_information) {}
  template <typename T>
  bool operator()(const T* pose, const T* m, T* residual) const {
    using std::atan2, std::sqrt;
    const T dx = m[0] - pose[0], dy = m[1] - pose[1];
    const T bearing = T(z_.y()) - atan2(dy, dx) + pose[2];  // wrapped as the angle manifold does
    Eigen::Matrix<T, 2, 1> e(T(z_.x()) - sqrt(dx * dx + dy * dy), bearing + (NormalizeAngle(ScalarPart(bearing)) - ScalarPart(bearing)));
    Eigen::Map<Eigen::Matrix<T, 2, 1>> r(residual);
    r = sqrt_information_.cast<T>() * e;
    return true;
  }
  Eigen::Vector2d z_;
  Eigen::Matrix2d sqrt_information_;
};

/// Upper-triangular U with U^T U = covariance^-1, so |U e|^2 = e^T Sigma^-1 e (one
/// SqrtInformation for both graphs: slam/pose_graph_cost.hpp).
Eigen::Matrix3d SqrtInformationOf(const Eigen::Matrix3d& covariance) {
  const Eigen::Matrix3d information = covariance.inverse();
  Eigen::Matrix3d U;
  if (!SqrtInformation(0.5 * (information + information.transpose()), &U))
    throw std::invalid_argument("landmark graph: odometry covariance is not symmetric positive definite");
  return U;
}

// Observations whose landmark the solution puts closer to their keyframe than the range's
// standard deviation are left out (true if there were any). At |m - t| -> 0 the
// range-bearing factor is singular: the bearing is undefined and its Jacobian grows as
// 1/|m - t|, so a landmark whose observations cannot be one point (two clutter detections
// the front end paired) can lower the cost by sitting on one of its keyframes, where that
// keyframe's bearing residual vanishes. Ceres then stops at |m - t| ~ 1e-9 m and the
// information matrix is numerically singular (held-out park lm10_0: its pose block reached
// 1.4e22, so no marginal existed). Within sigma_r the bearing means nothing even for a real
// landmark; no real post is that close to a robot.
bool LeaveOutAtTheSingularity(const LandmarkGraph& g, std::vector<bool>& left_out) {
  const double sigma_r = std::sqrt(g.observation_covariance(0, 0));
  bool any = false;
  for (size_t i = 0; i < g.observations.size(); ++i) {
    const RangeBearingConstraint& obs = g.observations[i];
    const auto it = g.landmarks.find(obs.landmark);
    if (left_out[i] || it == g.landmarks.end()) continue;
    if ((it->second - g.poses.at(static_cast<size_t>(obs.keyframe)).translation()).norm() < sigma_r)
      left_out[i] = any = true;
  }
  return any;
}

/// One solve without the observations left out; false (and no marginals) if it left out more.
bool SolveOnce(LandmarkGraph& g, const LandmarkGraphOptions& options, std::vector<bool>& left_out,
               LandmarkGraphSolution& solution) {
  solution = {};
  // Parameters: one (x, y, theta) block per keyframe, copied out of the SE2s and back.
  std::vector<double> x(3 * g.poses.size());
  for (size_t i = 0; i < g.poses.size(); ++i) {
    x[3 * i] = g.poses[i].x;
    x[3 * i + 1] = g.poses[i].y;
    x[3 * i + 2] = g.poses[i].theta;
  }
  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  PoseManifold pose_manifold;
  for (size_t i = 0; i < g.poses.size(); ++i) problem.AddParameterBlock(&x[3 * i], 3, &pose_manifold);
  problem.SetParameterBlockConstant(&x[0]);
  for (const auto& o : g.odometry) {
    problem.AddResidualBlock(new PoseGraphEdgeCost(o.T_from_to, SqrtInformationOf(FactorCovariance(o))), nullptr,
                             &x.at(3 * o.from), &x.at(3 * (o.from + 1)));
  }
  const Eigen::Matrix2d info_z = g.observation_covariance.inverse();
  const Eigen::Matrix2d sqrt_info_z =
      Eigen::LLT<Eigen::Matrix2d>(0.5 * (info_z + info_z.transpose())).matrixU();
  for (size_t i = 0; i < g.observations.size(); ++i) {
    const RangeBearingConstraint& obs = g.observations[i];
    const auto it = g.landmarks.find(obs.landmark);
    if (left_out[i] || it == g.landmarks.end()) continue;
    ceres::LossFunction* loss = options.huber_scale > 0 ? new ceres::HuberLoss(options.huber_scale) : nullptr;
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<RangeBearingFactor, 2, 3, 2>(
                                 new RangeBearingFactor(obs.z, sqrt_info_z)),
                             loss, &x.at(3 * obs.keyframe), it->second.data());
  }
  // A landmark seen by no kept observation would be a free block: drop it.
  for (auto it = g.landmarks.begin(); it != g.landmarks.end();) {
    if (!problem.HasParameterBlock(it->second.data())) it = g.landmarks.erase(it);
    else ++it;
  }
  if (options.hold_landmarks)
    for (auto& [key, m] : g.landmarks) problem.SetParameterBlockConstant(m.data());

  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver_options.max_num_iterations = options.max_iterations;
  solver_options.function_tolerance = options.function_tolerance;
  solver_options.num_threads = 1;
  solver_options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options, &problem, &summary);
  solution.termination = ceres::TerminationTypeToString(summary.termination_type);
  solution.usable = summary.IsSolutionUsable();
  solution.iterations = static_cast<int>(summary.iterations.size());
  solution.chi2_initial = 2.0 * summary.initial_cost;
  solution.chi2_final = 2.0 * summary.final_cost;
  solution.num_residuals = summary.num_residuals;
  for (size_t i = 0; i < g.poses.size(); ++i) g.poses[i] = SE2(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
  if (solution.usable && LeaveOutAtTheSingularity(g, left_out)) return false;

  solution.pose_covariances.assign(g.poses.size(), Eigen::Matrix3d::Zero());
  if (!(options.compute_covariance || options.joint_landmark_covariance) || !solution.usable || options.hold_landmarks)
    return true;
  // Marginals: selected inversion of the information matrix (slam/sparse_marginals.hpp).
  std::vector<double*> blocks;
  std::vector<std::pair<int, int>> requested;
  int offset = 0;
  for (size_t i = 1; i < g.poses.size(); ++i, offset += 3) {
    blocks.push_back(&x[3 * i]);
    requested.emplace_back(offset, 3);
  }
  const int first_landmark = offset;
  for (auto& [key, m] : g.landmarks) {
    blocks.push_back(m.data());
    requested.emplace_back(offset, 2);
    offset += 2;
  }
  const Eigen::SparseMatrix<double> H = InformationMatrix(problem, blocks);
  if (options.joint_landmark_covariance) {
    solution.landmark_joint_covariance = InverseTrailingBlock(H, first_landmark);
    if (solution.landmark_joint_covariance.size() == 0) return true;
  }
  if (options.compute_covariance) {
    const DiagonalBlocksOfInverse inverse = InverseDiagonalBlocks(H, requested);
    if (!inverse.ok) return true;
    size_t b = 0;
    for (size_t i = 1; i < g.poses.size(); ++i) solution.pose_covariances[i] = inverse.blocks[b++];
    for (const auto& [key, m] : g.landmarks) solution.landmark_covariances[key] = inverse.blocks[b++];
  }
  solution.covariance_ok = true;
  return true;
}

}  // namespace

LandmarkGraphSolution SolveLandmarkGraph(LandmarkGraph& g, const LandmarkGraphOptions& options) {
  LandmarkGraphSolution solution;
  if (g.poses.empty()) return solution;
  std::vector<bool> left_out(g.observations.size(), false);
  // Each round that returns false left out at least one more observation, so this ends.
  while (!SolveOnce(g, options, left_out, solution)) continue;
  solution.observations_left_out = static_cast<int>(std::count(left_out.begin(), left_out.end(), true));
  return solution;
}

}  // namespace slambox
