#pragma once
// FastSLAM's shared map storage (Montemerlo et al. 2002, Sec. 4 "Efficient
// implementation"): each particle's landmark EKFs live in a persistent, path-copying
// binary tree keyed by a non-negative landmark key. The tree is a complete binary trie
// on the key's bits (height h covers keys 0 .. 2^h - 1), so it is balanced by
// construction: a lookup visits h + 1 nodes and an update copies at most h + 1 nodes,
// h = ceil(log2(largest key + 1)). Copying a tree (resampling) copies one pointer.
// A node reachable only through uniquely owned nodes is modified in place instead of
// copied (no other tree can see it). Inner nodes keep the bounding box of their
// subtree's landmark means so range queries skip far subtrees.
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <vector>

namespace slambox {

/// One landmark's EKF (2x2) and its existence counter (Thrun, Table 13.2, i_n).
struct LandmarkGaussian {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();  ///< [m] world frame
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();  ///< [m^2]
  /// +1 per sighting, minus the detection probability at its range per miss in view
  /// (1 without an estimated rate); gone below 0.
  double counter = 1.0;
  /// With the sequential existence test instead: the log likelihood ratio "real" against
  /// "clutter" of its trials so far (slam/landmark_existence.hpp).
  double log_ratio = 0.0;
  /// Place recognition (slam/fastslam_constellation.cpp): the robot's travel when the
  /// landmark was created and last seen, and dead reckoning's heading variance then.
  double created_travel_m = 0.0;
  double seen_travel_m = 0.0;
  double seen_heading_variance_rad2 = 0.0;
};

struct LandmarkTreeNode {
  std::shared_ptr<LandmarkTreeNode> child[2];  ///< inner nodes; leaves have none
  LandmarkGaussian landmark;                   ///< leaves only
  Eigen::Vector2d box_min, box_max;            ///< [m] bounds of the means below (leaf: its mean)
};

/// A particle's map: a root and the trie height. Copying it shares every node.
struct LandmarkTree {
  std::shared_ptr<LandmarkTreeNode> root;
  int height = 0;  ///< keys 0 .. 2^height - 1 fit
  int size = 0;    ///< number of landmarks
};

/// The landmark stored under `key`, or nullptr.
const LandmarkGaussian* FindLandmark(const LandmarkTree& tree, int key);
/// Stores `landmark` under `key` (inserting or replacing); copies only the path to it.
void SetLandmark(LandmarkTree& tree, int key, const LandmarkGaussian& landmark);
/// Removes `key` if present; empty subtrees are pruned.
void EraseLandmark(LandmarkTree& tree, int key);

/// Calls fn(key, landmark) for every landmark, in key order.
void ForEachLandmark(const LandmarkTree& tree, const std::function<void(int, const LandmarkGaussian&)>& fn);
/// Keys of the landmarks whose means lie in the axis-aligned box [lo, hi], in key order.
std::vector<int> LandmarksInBox(const LandmarkTree& tree, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi);

/// Number of distinct nodes reachable from the given trees (shared nodes counted once):
/// the memory the particle set's maps occupy.
size_t CountDistinctNodes(const std::vector<const LandmarkTree*>& trees);

}  // namespace slambox
