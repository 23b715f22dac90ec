#pragma once
// Loop closures for ICP PoseSLAM: candidates are earlier keyframes close to the new one
// under the current estimate, within a window set by the uncertainty of their relative
// pose (Dijkstra projection over the pose graph, Bosse et al. 2003: the covariance of
// T_j_query composed along the most certain path of edges); each is matched globally in
// that window (slam/correlative_matcher.hpp), refined by ICP and verified.
#include <string>
#include <utility>
#include <vector>

#include "slam/icp.hpp"
#include "slam/pose_graph.hpp"

namespace slambox {

struct LoopClosureConfig {
  double min_travel_m = 8.0;          ///< [m] path between the keyframes before a loop may close
  double search_radius_m = 0.5;       ///< [m] base search radius (added to the uncertainty's)
  double radius_per_travel = 0.0;     ///< [m/m] radius growth per metre travelled between them
  double window_sigmas = 3.0;         ///< the window is this many standard deviations wide
  double max_search_radius_m = 8.0;   ///< [m] radius cap
  double search_angle_deg = 5.0;      ///< [deg] base angular window
  double max_search_angle_deg = 30.0; ///< [deg] angular window cap
  int max_candidates = 3;             ///< verifications per new keyframe, nearest first
  int min_keyframe_gap = 3;           ///< candidates closer than this many keyframes to a chosen one are skipped
  double max_rms_m = 0.05;            ///< [m] ICP fitness: RMS residual over inliers
  double min_inlier_ratio = 0.6;      ///< ICP overlap: inliers / source points
};

struct LoopCandidate {
  int keyframe = 0;
  double distance_m = 0.0;  ///< between the estimated positions
  double radius_m = 0.0;    ///< linear search window used
  double angle_rad = 0.0;   ///< angular search window used
};

/// Covariance of T_j_query for every node j, composed along the path of edges whose
/// position covariance trace is smallest (Dijkstra; edge covariance = information^-1,
/// poses from the current estimate). Edges with use_edge[e] false are skipped (empty:
/// all used). Nodes not reached, or only beyond max_trace_m2, get `unreached` * I.
std::vector<Eigen::Matrix3d> RelativeCovariances(const PoseGraph& graph, int query,
                                                 const std::vector<bool>& use_edge, double max_trace_m2,
                                                 double unreached = 1e6);

/// Covariance of T^-1 given T ~ (T, cov) over (x, y, theta) coordinates (first order).
Eigen::Matrix3d InverseCovariance(const SE2& T, const Eigen::Matrix3d& cov);

/// Search window (linear radius [m], angle [rad]) for a pair travel metres of path apart
/// whose relative pose has covariance relative_cov (null: no uncertainty term):
/// search_radius_m + radius_per_travel * travel + window_sigmas * sigma (sigma: the largest
/// standard deviation of the position block), capped; the same for the angle.
std::pair<double, double> LoopWindow(const Eigen::Matrix3d* relative_cov, double travel_m,
                                     const LoopClosureConfig& config);

/// Earlier keyframes j near `query` (index into positions), nearest first, at most
/// max_candidates, no two closer than min_keyframe_gap. The window of j: search_radius_m +
/// radius_per_travel * travel + window_sigmas * sigma (sigma: the largest standard deviation
/// of relative_cov[j]'s position block; 0 without relative_cov), capped; the same for the angle.
std::vector<LoopCandidate> FindLoopCandidates(const std::vector<SE2>& keyframe_poses,
                                              const std::vector<double>& path_m, int query,
                                              const LoopClosureConfig& config,
                                              const std::vector<Eigen::Matrix3d>& relative_cov = {});

struct LoopVerification {
  bool accepted = false;
  std::string reason;  ///< why rejected ("" when accepted)
};

/// Checks an ICP result for a loop: converged, not degenerate, fitness, overlap, and the
/// correction from the guess within the search radius.
LoopVerification VerifyLoopClosure(const IcpResult& r, const SE2& guess, double radius_m,
                                   const LoopClosureConfig& config);

}  // namespace slambox
