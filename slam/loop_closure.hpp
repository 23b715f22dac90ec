#pragma once
// Loop closures for ICP PoseSLAM: candidates are earlier keyframes close to the new one
// under the current estimate, within a radius that grows with the path travelled between
// them (a proxy for the relative pose's uncertainty); each is verified by ICP.
#include <string>
#include <vector>

#include "slam/icp.hpp"

namespace slambox {

struct LoopClosureConfig {
  double min_travel_m = 8.0;          ///< [m] path between the keyframes before a loop may close
  double search_radius_m = 1.0;       ///< [m] base search radius
  double radius_per_travel = 0.03;    ///< [m/m] radius growth per metre travelled between them
  double max_search_radius_m = 4.0;   ///< [m] radius cap
  int max_candidates = 3;             ///< ICP verifications per new keyframe, nearest first
  double max_rms_m = 0.05;            ///< [m] ICP fitness: RMS residual over inliers
  double min_inlier_ratio = 0.6;      ///< ICP overlap: inliers / source points
};

struct LoopCandidate {
  int keyframe = 0;
  double distance_m = 0.0;  ///< between the estimated positions
  double radius_m = 0.0;    ///< search radius used
};

/// Earlier keyframes j near `query` (index into positions), nearest first, at most max_candidates.
std::vector<LoopCandidate> FindLoopCandidates(const std::vector<SE2>& keyframe_poses,
                                              const std::vector<double>& path_m, int query,
                                              const LoopClosureConfig& config);

struct LoopVerification {
  bool accepted = false;
  std::string reason;  ///< why rejected ("" when accepted)
};

/// Checks an ICP result for a loop: converged, not degenerate, fitness, overlap, and the
/// correction from the guess within the search radius.
LoopVerification VerifyLoopClosure(const IcpResult& r, const SE2& guess, double radius_m,
                                   const LoopClosureConfig& config);

}  // namespace slambox
