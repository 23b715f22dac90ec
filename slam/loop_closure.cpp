#include "slam/loop_closure.hpp"

#include <algorithm>

namespace slambox {

std::vector<LoopCandidate> FindLoopCandidates(const std::vector<SE2>& poses, const std::vector<double>& path_m,
                                              int query, const LoopClosureConfig& config) {
  std::vector<LoopCandidate> out;
  const size_t q = static_cast<size_t>(query);
  for (int j = 0; j < query; ++j) {
    const double travel = path_m[q] - path_m[static_cast<size_t>(j)];
    if (travel < config.min_travel_m) continue;
    const double radius = std::min(config.search_radius_m + config.radius_per_travel * travel,
                                   config.max_search_radius_m);
    const double d = (poses[q].translation() - poses[static_cast<size_t>(j)].translation()).norm();
    if (d <= radius) out.push_back({j, d, radius});
  }
  std::sort(out.begin(), out.end(), [](const LoopCandidate& a, const LoopCandidate& b) {
    return a.distance_m < b.distance_m || (a.distance_m == b.distance_m && a.keyframe < b.keyframe);
  });
  if (static_cast<int>(out.size()) > config.max_candidates) out.resize(static_cast<size_t>(config.max_candidates));
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
