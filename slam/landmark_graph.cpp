#include "slam/landmark_graph.hpp"

#include <ceres/ceres.h>

#include <Eigen/Cholesky>

namespace slambox {

namespace {

template <typename T>
T WrapAngle(const T& a) {
  using std::atan2, std::cos, std::sin;
  return atan2(sin(a), cos(a));
}

struct OdometryFactor {
  OdometryFactor(const SE2& T_ij, const Eigen::Matrix3d& sqrt_information)
      : T_ij_(T_ij), sqrt_information_(sqrt_information) {}
  template <typename T>
  bool operator()(const T* pi, const T* pj, T* residual) const {
    using std::cos, std::sin;
    const T c = cos(pi[2]), s = sin(pi[2]), dx = pj[0] - pi[0], dy = pj[1] - pi[1];
    Eigen::Matrix<T, 3, 1> e(c * dx + s * dy - T(T_ij_.x), -s * dx + c * dy - T(T_ij_.y),
                             WrapAngle(pj[2] - pi[2] - T(T_ij_.theta)));
    Eigen::Map<Eigen::Matrix<T, 3, 1>> r(residual);
    r = sqrt_information_.cast<T>() * e;
    return true;
  }
  SE2 T_ij_;
  Eigen::Matrix3d sqrt_information_;
};

struct RangeBearingFactor {
  RangeBearingFactor(const Eigen::Vector2d& z, const Eigen::Matrix2d& sqrt_information)
      : z_(z), sqrt_information_(sqrt_information) {}
  template <typename T>
  bool operator()(const T* pose, const T* m, T* residual) const {
    using std::atan2, std::sqrt;
    const T dx = m[0] - pose[0], dy = m[1] - pose[1];
    Eigen::Matrix<T, 2, 1> e(T(z_.x()) - sqrt(dx * dx + dy * dy), WrapAngle(T(z_.y()) - atan2(dy, dx) + pose[2]));
    Eigen::Map<Eigen::Matrix<T, 2, 1>> r(residual);
    r = sqrt_information_.cast<T>() * e;
    return true;
  }
  Eigen::Vector2d z_;
  Eigen::Matrix2d sqrt_information_;
};

/// L^T with L L^T = Sigma^-1, so |L^T e|^2 = e^T Sigma^-1 e.
template <int N>
Eigen::Matrix<double, N, N> SqrtInformation(const Eigen::Matrix<double, N, N>& covariance) {
  const Eigen::Matrix<double, N, N> information = covariance.inverse();
  return Eigen::LLT<Eigen::Matrix<double, N, N>>(0.5 * (information + information.transpose())).matrixL().transpose();
}

}  // namespace

LandmarkGraphSolution SolveLandmarkGraph(LandmarkGraph& g, const LandmarkGraphOptions& options) {
  LandmarkGraphSolution solution;
  if (g.poses.empty()) return solution;
  ceres::Problem problem;
  for (auto& p : g.poses) problem.AddParameterBlock(p.data(), 3);
  problem.SetParameterBlockConstant(g.poses[0].data());
  // A floor on the odometry covariance keeps a standing-still segment invertible.
  const Eigen::Matrix3d floor = Eigen::Vector3d(1e-8, 1e-8, 1e-8).asDiagonal();
  for (const auto& o : g.odometry) {
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<OdometryFactor, 3, 3, 3>(
                                 new OdometryFactor(o.T_from_to, SqrtInformation<3>(o.covariance + floor))),
                             nullptr, g.poses.at(o.from).data(), g.poses.at(o.from + 1).data());
  }
  const Eigen::Matrix2d sqrt_info_z = SqrtInformation<2>(g.observation_covariance);
  for (const auto& obs : g.observations) {
    const auto it = g.landmarks.find(obs.landmark);
    if (it == g.landmarks.end()) continue;
    ceres::LossFunction* loss = options.huber_scale > 0 ? new ceres::HuberLoss(options.huber_scale) : nullptr;
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<RangeBearingFactor, 2, 3, 2>(
                                 new RangeBearingFactor(obs.z, sqrt_info_z)),
                             loss, g.poses.at(obs.keyframe).data(), it->second.data());
  }
  // A landmark seen by no kept observation would be a free block: drop it.
  for (auto it = g.landmarks.begin(); it != g.landmarks.end();) {
    if (!problem.HasParameterBlock(it->second.data())) it = g.landmarks.erase(it);
    else ++it;
  }

  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver_options.max_num_iterations = options.max_iterations;
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
  for (auto& p : g.poses) p(2) = NormalizeAngle(p(2));

  solution.pose_covariances.assign(g.poses.size(), Eigen::Matrix3d::Zero());
  if (!options.compute_covariance || !solution.usable) return solution;
  ceres::Covariance::Options cov_options;
  cov_options.algorithm_type = ceres::SPARSE_QR;
  cov_options.num_threads = 1;
  ceres::Covariance covariance(cov_options);
  std::vector<std::pair<const double*, const double*>> blocks;
  for (size_t i = 1; i < g.poses.size(); ++i) blocks.emplace_back(g.poses[i].data(), g.poses[i].data());
  for (const auto& [key, m] : g.landmarks) blocks.emplace_back(m.data(), m.data());
  if (!covariance.Compute(blocks, &problem)) return solution;
  solution.covariance_ok = true;
  for (size_t i = 1; i < g.poses.size(); ++i) {
    Eigen::Matrix<double, 3, 3, Eigen::RowMajor> C;
    covariance.GetCovarianceBlock(g.poses[i].data(), g.poses[i].data(), C.data());
    solution.pose_covariances[i] = C;
  }
  for (const auto& [key, m] : g.landmarks) {
    Eigen::Matrix<double, 2, 2, Eigen::RowMajor> C;
    covariance.GetCovarianceBlock(m.data(), m.data(), C.data());
    solution.landmark_covariances[key] = C;
  }
  return solution;
}

}  // namespace slambox
