#pragma once
// Matching estimated poses to ground truth by timestamp, as evo's
// sync.associate_trajectories does: walk the trajectory with fewer poses (the estimate
// on ties) and take, for each of its stamps, the nearest stamp of the other one (first
// on ties), kept when |dt| <= max_time_diff_s. Optionally (evo lacks it, evo #439/#512)
// ground truth is linearly interpolated at every estimate stamp inside its time span.
#include <vector>

#include "core/stream.hpp"

namespace slambox {

struct AssociationOptions {
  double max_time_diff_s = 0.01;  ///< [s] evo's --t_max_diff default
  bool interpolate = false;       ///< interpolate ground truth instead of nearest stamp
};

/// Matched poses, in the order evo produces them (time order of the walked trajectory).
struct Association {
  std::vector<double> t_s;         ///< the estimate's stamp of each match
  std::vector<SE2> groundtruth;    ///< T_world_robot, true
  std::vector<SE2> estimate;       ///< T_world_robot, estimated
  std::vector<int> estimate_index; ///< index into the estimate's pose list
  std::vector<double> distance_m;  ///< ground-truth distance travelled at the match
};

/// Both trajectories must be sorted by time (ReadTum and Estimate guarantee it).
Association Associate(const std::vector<StampedPose>& groundtruth, const std::vector<StampedPose>& estimate,
                      const AssociationOptions& options = {});

/// Pose at time t by linear interpolation between the bracketing poses; the heading is
/// interpolated along the shorter arc, theta_0 + u wrap(theta_1 - theta_0). An exact
/// stamp returns that pose unchanged. False when t is outside the trajectory's span.
bool InterpolatePose(const std::vector<StampedPose>& trajectory, double t_s, SE2& pose, int& lower_index,
                     double& fraction);

/// Cumulative distance travelled [m] at every pose (0 at the first).
std::vector<double> CumulativeDistance(const std::vector<SE2>& poses);

}  // namespace slambox
