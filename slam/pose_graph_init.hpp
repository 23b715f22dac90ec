#pragma once
// Initial guesses for a 2D pose graph, for files with edges only or poor guesses.
//  - Spanning tree: compose measurements outward from the anchor along a tree that
//    prefers odometry edges (so a chain-connected graph gets exactly its odometry chain).
//  - LAGO (Carlone, Aragues, Castellanos, Bona, "A fast and accurate approximation for
//    planar pose graph optimization", IJRR 2014): orientations first, by linear least
//    squares over angle differences made consistent around cycles (2 pi k regularization
//    from the tree), then positions by linear least squares given those orientations.
//  - Chordal (Martinec & Pajdla 2007; Carlone, Tron, Daniilidis, Dellaert, "Initialization
//    techniques for 3D SLAM", ICRA 2015): each rotation as a unit vector, the chordal
//    distances |R_j - R_i R_ij|_F^2 minimized linearly with the unit norm dropped, then
//    normalized; no 2 pi ambiguity to resolve, so large rotation noise on the loop
//    closures does not throw it off as it can LAGO's tree-based unwrapping. Positions as LAGO.
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

/// Chordal initialization: orientations by the chordal relaxation, then positions as LAGO.
std::vector<SE2> ChordalInitialization(const PoseGraph& graph);

/// The chordal relaxation's orientations ([rad], in (-pi, pi]; the anchor keeps its own).
std::vector<double> ChordalOrientations(const PoseGraph& graph, const SpanningTree& tree);

enum class LandmarkPlacement {
  kFirstObservation,  ///< from the first edge observing it
  kMean,              ///< the mean over every edge observing it (the least-squares point for equal, isotropic information)
};

/// Each observed landmark placed from its edges at `poses`; unobserved ones keep their
/// graph value.
std::vector<Eigen::Vector2d> LandmarksFromObservations(const PoseGraph& graph, const std::vector<SE2>& poses,
                                                       LandmarkPlacement placement = LandmarkPlacement::kMean);

}  // namespace slambox
