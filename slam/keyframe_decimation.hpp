#pragma once
// A landmark graph with fewer keyframes, for solves whose only job is a good guess (the
// periodic solves of slam/graphslam.hpp). Every `stride`-th keyframe is kept, and the last;
// the odometry between two kept keyframes is the composition of the factors between them,
// its covariance propagated to first order (core/se2's ComposeCovariance: the factors are
// independent); only the kept keyframes' observations stay. A solve of it costs about
// 1/stride of the full graph's (keyframes and observations both shrink by the stride), and
// it has the full graph's shape: the dropped keyframes only added more of the same evidence.
// After the solve the dropped keyframes follow the kept one before them rigidly.
#include <vector>

#include "slam/landmark_graph.hpp"

namespace slambox {

struct DecimatedGraph {
  LandmarkGraph graph;    ///< landmarks copied; keyframe i is full keyframe kept[i]
  std::vector<int> kept;  ///< ascending; first 0, last the full graph's last keyframe
};

/// The smallest stride that keeps at most `max_keyframes` of the keyframes 0..last_keyframe:
/// ceil((last_keyframe + 1) / max_keyframes); 1 without a cap (max_keyframes 0).
int DecimationStride(int last_keyframe, int max_keyframes);

/// `full.odometry` must chain every keyframe to the next (constraint k: from k to k + 1).
DecimatedGraph DecimateKeyframes(const LandmarkGraph& full, int stride);

/// Writes the solved poses and landmarks of `d` into `full`: a kept keyframe takes its
/// solved pose, a dropped one keeps its pose relative to the kept keyframe before it
/// (its guess in `full`); a landmark the decimated graph no longer has keeps its guess.
void SpreadDecimatedSolution(const DecimatedGraph& d, LandmarkGraph& full);

}  // namespace slambox
