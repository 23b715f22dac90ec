#include "slam/loop_closure.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <queue>

namespace slambox {

Eigen::Matrix3d InverseCovariance(const SE2& T, const Eigen::Matrix3d& cov) {
  // u = -R^T t, phi = -theta: du/dt = -R^T, du/dtheta = (u_y, -u_x).
  const SE2 inv = T.inverse();
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  J.topLeftCorner<2, 2>() = -T.rotation().transpose();
  J(0, 2) = inv.y;
  J(1, 2) = -inv.x;
  J(2, 2) = -1.0;
  return J * cov * J.transpose();
}

std::vector<Eigen::Matrix3d> RelativeCovariances(const PoseGraph& graph, int query, const std::vector<bool>& use_edge,
                                                 double max_trace_m2, double unreached) {
  const size_t n = graph.poses.size();
  std::vector<std::vector<int>> adjacent(n);
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    if (!use_edge.empty() && !use_edge[e]) continue;
    adjacent[static_cast<size_t>(graph.edges[e].from)].push_back(static_cast<int>(e));
    adjacent[static_cast<size_t>(graph.edges[e].to)].push_back(static_cast<int>(e));
  }
  std::vector<Eigen::Matrix3d> cov(n, unreached * Eigen::Matrix3d::Identity());
  std::vector<double> trace(n, std::numeric_limits<double>::infinity());
  std::vector<bool> done(n, false);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  const size_t q = static_cast<size_t>(query);
  cov[q].setZero();
  trace[q] = 0.0;
  open.push({0.0, query});
  while (!open.empty()) {
    const auto [t, i] = open.top();
    open.pop();
    const size_t ui = static_cast<size_t>(i);
    if (done[ui] || t > trace[ui]) continue;
    done[ui] = true;
    const SE2 T_i_q = Between(graph.poses[ui], graph.poses[q]);
    for (int e : adjacent[ui]) {
      const PoseGraphEdge& edge = graph.edges[static_cast<size_t>(e)];
      const int j = edge.from == i ? edge.to : edge.from;
      const size_t uj = static_cast<size_t>(j);
      if (done[uj]) continue;
      // T_j_q = T_j_i * T_i_q, T_j_i from the estimate, its covariance from the edge.
      const SE2 T_j_i = Between(graph.poses[uj], graph.poses[ui]);
      const Eigen::Matrix3d edge_cov = edge.information.inverse();
      const Eigen::Matrix3d cov_j_i = edge.from == j ? edge_cov : InverseCovariance(T_j_i.inverse(), edge_cov);
      const Eigen::Matrix3d c = ComposeCovariance(T_j_i, cov_j_i, T_i_q, cov[ui]);
      const double tr = c(0, 0) + c(1, 1);
      if (tr >= trace[uj] || tr > max_trace_m2) continue;
      trace[uj] = tr;
      cov[uj] = c;
      open.push({tr, j});
    }
  }
  return cov;
}

std::pair<double, double> LoopWindow(const Eigen::Matrix3d* relative_cov, double travel_m,
                                     const LoopClosureConfig& config) {
  constexpr double kDegToRad = M_PI / 180.0;
  double sigma_xy = 0.0, sigma_theta = 0.0;
  if (relative_cov) {
    const Eigen::Matrix2d P = relative_cov->topLeftCorner<2, 2>();
    sigma_xy = std::sqrt(std::max(Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(P, Eigen::EigenvaluesOnly).eigenvalues()(1), 0.0));
    sigma_theta = std::sqrt(std::max((*relative_cov)(2, 2), 0.0));
  }
  const double radius = std::min(config.search_radius_m + config.radius_per_travel * travel_m + config.window_sigmas * sigma_xy,
                                 config.max_search_radius_m);
  const double angle = std::min(config.search_angle_deg * kDegToRad + config.window_sigmas * sigma_theta,
                                config.max_search_angle_deg * kDegToRad);
  return {radius, angle};
}

std::vector<LoopCandidate> FindLoopCandidates(const std::vector<SE2>& poses, const std::vector<double>& path_m,
                                              int query, const LoopClosureConfig& config,
                                              const std::vector<Eigen::Matrix3d>& relative_cov) {
  std::vector<LoopCandidate> all;
  const size_t q = static_cast<size_t>(query);
  for (int j = 0; j < query; ++j) {
    const size_t uj = static_cast<size_t>(j);
    const double travel = path_m[q] - path_m[uj];
    if (travel < config.min_travel_m) continue;
    const auto [radius, angle] = LoopWindow(relative_cov.empty() ? nullptr : &relative_cov[uj], travel, config);
    const double d = (poses[q].translation() - poses[uj].translation()).norm();
    if (d <= radius) all.push_back({j, d, radius, angle});
  }
  std::sort(all.begin(), all.end(), [](const LoopCandidate& a, const LoopCandidate& b) {
    return a.distance_m < b.distance_m || (a.distance_m == b.distance_m && a.keyframe < b.keyframe);
  });
  std::vector<LoopCandidate> out;
  for (const LoopCandidate& c : all) {
    if (static_cast<int>(out.size()) >= config.max_candidates) break;
    const bool near_chosen = std::any_of(out.begin(), out.end(), [&](const LoopCandidate& o) {
      return std::abs(o.keyframe - c.keyframe) < config.min_keyframe_gap;
    });
    if (!near_chosen) out.push_back(c);
  }
  return out;
}

LoopVerification VerifyLoopClosure(const IcpResult& r, const SE2& guess, double radius_m,
                                   const LoopClosureConfig& config) {
  if (!r.converged) return {false, "icp did not converge"};
  if (r.degenerate) return {false, "degenerate"};
  if (r.rms_residual_m > config.max_rms_m) return {false, "fitness"};
  if (r.num_inliers < config.min_inlier_ratio * r.num_source) return {false, "overlap"};
  if ((r.T_target_source.translation() - guess.translation()).norm() > radius_m)
    return {false, "correction beyond search radius"};
  return {true, ""};
}

}  // namespace slambox
