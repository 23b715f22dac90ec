#pragma once
// A guess for the end solve of slam/graphslam.hpp made after the run: the landmark graph
// solved as it grew (its first K keyframes, then every K more; iSAM's periodic batch steps,
// Kaess et al. 2008, replayed). Each solve starts from the last one's solution; the keyframes
// added since are composed onto it with the front end's motion, which holds what the filter's
// landmarks corrected, and a landmark seen for the first time starts at its first observation.
// A loop is then closed while it is fresh, from a smooth graph, instead of at the end from the
// filter's poses, which jump where it closed (Levenberg-Marquardt can stop in a fold there).
// Past `max_keyframes` a solve is of every stride-th keyframe (slam/keyframe_decimation.hpp;
// stride = ceil(keyframes / max_keyframes)) and comes every K x stride keyframes, so each
// costs about the same and the replay about log(n) of them past the cap.
#include <vector>

#include "slam/landmark_graph.hpp"

namespace slambox {

/// A new keyframe's guess on a graph solved as it grows: the previous keyframe's solved pose
/// composed with the front end's motion between the two (it holds what the filter's landmarks
/// corrected; composed with odometry instead, held-out park lm4_8 ended at 26.4 m ATE against
/// 5.5 m; slam/README_landmark_slam.md) — unless that motion is a jump of the filter, not
/// motion: where it differs from the odometry factor between the two keyframes by more than
/// `jump_gate_chi2` (squared Mahalanobis distance under the factor's covariance; 0 = never),
/// the odometry's motion is composed instead. A filter jumps where it closes a loop or takes
/// an update of many sigmas (slam/ekf_slam.hpp, relinearize_step_prob); composed, the jump
/// puts every later keyframe of the growing graph where the filter's landmarks were, which
/// the next solve may not undo (held-out park lm3_9: every replay in a fold).
SE2 ComposedMotion(const SE2& solved_previous, const SE2& frontend_previous, const SE2& frontend_now,
                   const OdometryConstraint& odometry, double jump_gate_chi2);

/// Whether a growing graph is solved again at `keyframe`: every `solve_every_keyframes` x the
/// decimation stride (slam/keyframe_decimation.hpp) since the last solve.
bool GrowingGraphSolveDue(int keyframe, int last_solve_keyframe, int solve_every_keyframes, int max_keyframes);

struct GrowthReplaySettings {
  int solve_every_keyframes = 100;  ///< K [keyframes]
  int max_keyframes = 1000;         ///< [keyframes] solved at most (0 = all)
  double jump_gate_chi2 = 0.0;      ///< a front-end motion this far from the odometry's is not composed (ComposedMotion)
  LandmarkGraphOptions solver;      ///< the marginals are never computed
};

/// `full`: the final graph; its landmarks' keys say which landmarks exist (their positions
/// are not used), its poses are not used. `frontend_poses`: the front end's pose at each
/// keyframe. Returns the graph with the poses and landmarks after the replay's last solve
/// (keyframes after it composed as in ComposedMotion).
LandmarkGraph ReplayGrowth(const LandmarkGraph& full, const std::vector<SE2>& frontend_poses,
                           const GrowthReplaySettings& settings);

}  // namespace slambox
