#pragma once
// Initial guesses for a 2D pose graph, for files with edges only or poor guesses.
//  - Spanning tree: compose measurements outward from the anchor along a tree that
//    prefers odometry edges (so a chain-connected graph gets exactly its odometry chain).
//  - LAGO (Carlone, Aragues, Castellanos, Bona, "A fast and accurate approximation for
//    planar pose graph optimization", IJRR 2014): orientations first, by linear least
//    squares over angle differences made consistent around cycles (2 pi k regularization
//    from the tree), then positions by linear least squares given those orientations.
// Poses not connected to the anchor keep their input values.
// Landmarks (pose-only initializers do not place them): from their observations at the
// initialized poses, l = t_i + R_i z.
#include <Eigen/Core>
#include <vector>

#include "core/se2.hpp"
#include "slam/pose_graph.hpp"

namespace slambox {

struct SpanningTree {
  std::vector<int> parent_edge;  ///< edge joining each pose to its parent; -1 at the anchor / unreached
  std::vector<int> order;        ///< reached poses, parents before children (anchor first)
  std::vector<double> theta_unwrapped;  ///< [rad] anchor's theta + tree sum of measured angles, no wrap
};

/// Tree over the edges from graph.anchor. prefer_odometry: fewest loop-closure edges
/// first (0-1 BFS; the odometry chain); else fewest edges (BFS, the shallowest tree, so
/// least drift accumulates along any tree path).
SpanningTree BuildSpanningTree(const PoseGraph& graph, bool prefer_odometry = true);

/// Poses composed along the spanning tree (the odometry chain where it exists).
std::vector<SE2> SpanningTreeInitialization(const PoseGraph& graph);

/// LAGO-style orientation-then-position linear initialization.
std::vector<SE2> LagoInitialization(const PoseGraph& graph);

/// LAGO's first phase alone: orientations (unwrapped, [rad]) of every pose.
std::vector<double> LagoOrientations(const PoseGraph& graph, const SpanningTree& tree);

enum class LandmarkPlacement {
  kFirstObservation,  ///< from the first edge observing it
  kMean,              ///< the mean over every edge observing it (the least-squares point for equal, isotropic information)
};

/// Each observed landmark placed from its edges at `poses`; unobserved ones keep their
/// graph value.
std::vector<Eigen::Vector2d> LandmarksFromObservations(const PoseGraph& graph, const std::vector<SE2>& poses,
                                                       LandmarkPlacement placement = LandmarkPlacement::kMean);

}  // namespace slambox
