#include "core/finite_estimate.hpp"

#include <algorithm>
#include <cmath>

namespace slambox {
namespace {
bool Finite(const SE2& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta); }
}  // namespace

Estimate FiniteEstimate(const Estimate& in) {
  Estimate out = in;
  out.trajectory.clear();
  for (PoseEstimate p : in.trajectory) {
    if (!std::isfinite(p.t_s) || !Finite(p.pose)) break;
    if (p.has_covariance && !p.covariance.allFinite()) {
      p.has_covariance = false;
      p.covariance.setZero();
    }
    out.trajectory.push_back(p);
  }
  out.landmarks.clear();
  for (LandmarkEstimate l : in.landmarks) {
    if (!l.position.allFinite()) continue;
    if (l.has_covariance && !l.covariance.allFinite()) {
      l.has_covariance = false;
      l.covariance.setZero();
    }
    out.landmarks.push_back(l);
  }
  std::erase_if(out.map_points, [](const Eigen::Vector2d& p) { return !p.allFinite(); });
  std::erase_if(out.loop_closures, [](const LoopClosureRecord& c) {
    return !std::isfinite(c.t_from_s) || !std::isfinite(c.t_to_s) || !Finite(c.T_from_to);
  });
  for (auto& [name, series] : out.diagnostics)
    std::erase_if(series, [](const auto& tv) { return !std::isfinite(tv.first) || !std::isfinite(tv.second); });
  for (ParticleSnapshot& s : out.particles) {
    ParticleSnapshot kept{s.t_s, {}, {}};
    for (std::size_t i = 0; i < s.poses.size(); ++i)
      if (Finite(s.poses[i]) && (i >= s.weights.size() || std::isfinite(s.weights[i]))) {
        kept.poses.push_back(s.poses[i]);
        if (i < s.weights.size()) kept.weights.push_back(s.weights[i]);
      }
    s = std::move(kept);
  }
  // Pose-graph nodes are indexed by the edges: a non-finite node empties the view.
  if (!std::all_of(in.pose_graph.nodes.begin(), in.pose_graph.nodes.end(), Finite)) out.pose_graph = {};
  return out;
}

}  // namespace slambox
