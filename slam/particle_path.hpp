#pragma once
// A particle's trajectory as a persistent singly linked list, newest pose first: a child
// after resampling shares its parent's whole history, so copying a particle is O(1) and
// the histories of all particles form the ancestry tree (Montemerlo 2002; Bailey et al.
// 2006 read particle depletion off it).
#include <memory>
#include <vector>

#include "core/se2.hpp"

namespace slambox {

struct PathNode {
  double t_s = 0.0;
  SE2 pose;  ///< T_world_robot
  std::shared_ptr<PathNode> parent;

  PathNode(double t, const SE2& p, std::shared_ptr<PathNode> up) : t_s(t), pose(p), parent(std::move(up)) {}
  PathNode(const PathNode&) = delete;
  PathNode& operator=(const PathNode&) = delete;
  /// Iterative release: a long uniquely owned history would otherwise be freed by one
  /// recursive destructor call per pose and overflow the stack.
  ~PathNode() {
    std::shared_ptr<PathNode> next = std::move(parent);
    while (next && next.use_count() == 1) next = std::move(next->parent);
  }
};

using PathPtr = std::shared_ptr<PathNode>;

/// Appends (t, pose); when the newest node already has time t it is replaced instead
/// (a measurement update moved the pose at the same stream time).
inline PathPtr ExtendPath(const PathPtr& path, double t_s, const SE2& pose) {
  if (path && path->t_s == t_s) return std::make_shared<PathNode>(t_s, pose, path->parent);
  return std::make_shared<PathNode>(t_s, pose, path);
}

/// Dead reckoning's variance accrued by an odometry time: the same for every particle's path
/// (slam/fastslam_closure.hpp relaxes a path by it).
struct DriftSample {
  double t_s = 0;
  double heading_rad2 = 0;    ///< [rad^2] heading variance summed over every step until t_s
  double translation_m2 = 0;  ///< [m^2] translation variance summed over every step until t_s
};

/// The poses oldest first.
inline std::vector<const PathNode*> PathPoses(const PathPtr& path) {
  std::vector<const PathNode*> nodes;
  for (const PathNode* n = path.get(); n; n = n->parent.get()) nodes.push_back(n);
  return {nodes.rbegin(), nodes.rend()};
}

}  // namespace slambox
