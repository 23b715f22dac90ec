#pragma once
// `slambox optimize --init`: which initial guess a pose graph is solved from. `auto` solves
// from every cheap one (the file's guess, LAGO, chordal, the odometry chain: milliseconds
// each), continues an attempt the iteration cap stopped below every converged objective,
// and keeps the lowest converged objective (chi2, or with a kernel its robust sum).
#include <map>
#include <string>
#include <vector>

#include "slam/g2o_io.hpp"
#include "slam/pose_graph.hpp"

namespace slambox {

enum class InitMethod { kAuto, kFile, kLago, kChordal, kOdometry };
/// The --init names, the one list of them.
const std::map<std::string, InitMethod>& InitMethodNames();
std::string InitName(InitMethod m);

/// One initial guess solved: the method, its cost and the solution.
struct InitAttempt {
  InitMethod init;
  double init_time_s = 0.0;
  PoseGraph graph;  ///< the solution (solved in place from the guess)
  PoseGraphSolveResult result;
  int robust_stages = 1;  ///< solves of the graduated kernel schedule (slam/pose_graph_graduated.hpp)
};

/// `file`'s graph initialized by `method` (landmarks, but for kFile, at the mean of their
/// observations from the initialized poses) and solved; for the odometry chain and the
/// file's guess (not made from the loop closures, so not bent by outliers among them), with
/// a non-convex kernel whose loop closures disagree with the guess (GraduatedDecades > 0),
/// also through the graduated schedule from the same guess (slam/pose_graph_graduated.hpp):
/// better from a drifted chain, worse where the guess already sits near the inliers'
/// optimum and the early, nearly quadratic solves let the outliers pull it away; the lower
/// robust objective decides. The plain solve first.
std::vector<InitAttempt> SolveFrom(const PoseGraphFile& file, InitMethod method, const PoseGraphSolveOptions& options);

/// The usable attempt that stopped at the iteration cap (NO_CONVERGENCE) below every
/// converged chi2, if any converged, solved once more from where it stopped (its
/// iterations and times add up).
void ContinueTheLowestStalled(std::vector<InitAttempt>& attempts, const PoseGraphSolveOptions& options);

/// The requested initial guess solved as SolveFrom does, but graduated only from the one of
/// the chained guesses (file, odometry) with the lower chi2; for kAuto every guess but one
/// equal to an earlier one (within 1e-6 m / rad: e.g. a file whose VERTEX lines are its
/// odometry chain); the chosen one first. Throws
/// InputError (naming `path`) for kFile when the file has no complete guess.
std::vector<InitAttempt> SolveWithInit(const PoseGraphFile& file, InitMethod init, const std::string& path,
                                       const PoseGraphSolveOptions& options);

}  // namespace slambox
