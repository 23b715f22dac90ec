#pragma once
// Graduated non-convexity for a pose graph with a non-convex kernel on its loop closures
// (DCS, Cauchy). From a poor initial guess (an odometry chain that has drifted) every true
// loop closure has a huge chi2 and a kernel at its final scale rejects it (DCS's weight
// 4 Phi^2 / (Phi + chi2)^2 is then ~0), so the loops never close and the outliers stay as
// harmless as the inliers. Solved instead with the kernel's scale 10^K times larger, K the
// decades by which the median loop-closure chi2 at the guess exceeds the scale (at most
// kMaxDecades), then divided by 10 per solve, each warm-started from the last, down to the
// requested scale: Yang, Antonante, Tzoumas, Carlone, "Graduated non-convexity for robust
// spatial perception" (RA-L 2020), in decade steps. A guess whose loops already agree
// (K = 0), no kernel, or the convex Huber: one plain solve, as SolvePoseGraph.
#include "slam/pose_graph.hpp"

namespace slambox {

struct GraduatedSolveResult {
  PoseGraphSolveResult result;  ///< of the last solve; chi2_initial, iterations, time_s of all
  int stages = 1;               ///< solves run (K + 1)
  double first_scale = 0.0;     ///< the kernel scale of the first solve
};

inline constexpr int kMaxDecades = 8;
inline constexpr int kStageIterations = 20;  ///< cap of each solve before the last

/// The decades K above (0 without a non-convex kernel or loop closures).
int GraduatedDecades(const PoseGraph& graph, const PoseGraphSolveOptions& options);

/// SolvePoseGraph through the schedule above, in place.
GraduatedSolveResult SolvePoseGraphGraduated(PoseGraph& graph, const PoseGraphSolveOptions& options);

}  // namespace slambox
