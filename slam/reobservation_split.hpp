#pragma once
// Splitting every landmark where it is re-observed after leaving the sensor's view, so the
// smoother decides each such re-observation (a loop closure) itself (issue 14, `forest`).
// The EKF front end tracks a landmark reliably while it stays in view; a re-observation
// after drift is where it fails, and a wrong one is a false loop closure the smoothed graph
// then fits consistently (chi2 per degree of freedom about 1 on forest seed 11: nothing
// points at it). Split at those re-observations, the graph holds only what the front end
// is good at; slam/smoother_merges.hpp then merges the segments back, jointly, under the
// smoother's consistent marginals. A segment that the front end joined correctly with a
// small uncertainty merges back alone (its gate holds no other landmark), so splitting
// generously costs a re-merge, not accuracy.
// A landmark observed at keyframes k1 < k2 (consecutive among its observations) starts a
// new segment at k2 if at some keyframe between them it was outside the sensor's range or
// field of view as seen from that keyframe's pose (the graph's current solution), and if
// dead reckoning alone would leave the re-observation ambiguous: with the odometry's
// relative pose T_12 ~ (T, Sigma_12) composed over k1..k2 and the landmark p in k1's frame,
// its predicted position R^T (p - t) in k2's frame has covariance C = J Sigma_12 J^T +
// 2 G R G^T (J its Jacobian in T_12, G that of (r cos b, r sin b), R the range-bearing
// noise of either observation), and a gate of C expects mu = density pi gate sqrt(det C)
// other landmarks (slam/smoother_merges.hpp's test). Below the merge threshold the front
// end cannot have paired it wrongly for want of certainty, and it is not split.
#include <Eigen/Core>
#include <map>
#include <vector>

#include "slam/landmark_graph.hpp"
#include "slam/smoother_merges.hpp"

namespace slambox {

struct SensorFootprint {
  double range_max_m = 0.0;
  double half_fov_rad = M_PI;
};

/// A later segment of a landmark: from this keyframe on, its observations name `key`.
struct LandmarkSegment {
  int first_keyframe = 0;
  int key = 0;
};

struct ReobservationSplit {
  std::map<int, std::vector<LandmarkSegment>> segments;  ///< landmark key -> its later segments, by keyframe
  std::map<int, Eigen::Vector2d> guesses;                ///< new key -> position (mean of its observations' inverse)
};

/// Renames the observations of `graph` (in keyframe order) by segment, splitting where mu
/// reaches test.fake_probability; new keys count up from `first_free_key`. Landmarks not in
/// graph.landmarks are left alone.
ReobservationSplit SplitAtReobservations(LandmarkGraph& graph, const SensorFootprint& footprint,
                                         const MergeSearchSettings& test, int first_free_key);

/// Detection z at keyframe k of a landmark at m (in the graph's frame) seen from keyframe
/// k1, by dead reckoning alone: m taken into k1's frame by the graph's pose, carried to k's
/// frame by the odometry between them (either order), minus the detection's point; both in
/// k's frame. C as above (odometry covariance composed over the keyframes between, plus the
/// range-bearing noise of two observations).
struct DeadReckonedDifference {
  Eigen::Vector2d difference = Eigen::Vector2d::Zero();  ///< [m] predicted point - detected point
  Eigen::Matrix2d C = Eigen::Matrix2d::Zero();
};
DeadReckonedDifference DeadReckoned(const LandmarkGraph& graph, int k1, int k, const Eigen::Vector2d& m,
                                    const Eigen::Vector2d& z);

/// mu of the re-observation at keyframe k2 > k1, with bearing-range z, of a landmark at m
/// last seen at keyframe k1 (see above).
double ReobservationAmbiguity(const LandmarkGraph& graph, int k1, int k2, const Eigen::Vector2d& m,
                              const Eigen::Vector2d& z, const MergeSearchSettings& test);

/// The key of landmark `key`'s segment at `keyframe` (itself before its first split).
int SegmentKey(const ReobservationSplit& split, int key, int keyframe);

}  // namespace slambox
