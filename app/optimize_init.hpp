#pragma once
// `slambox optimize --init`: which initial guess a pose graph is solved from. `auto` solves
// from every cheap one (the file's guess, LAGO, chordal, the odometry chain: milliseconds
// each), continues an attempt the iteration cap stopped below every converged chi2, and
// keeps the lowest converged chi2.
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
};

/// `file`'s graph initialized by `method` (landmarks, but for kFile, at the mean of their
/// observations from the initialized poses) and solved.
InitAttempt SolveFrom(const PoseGraphFile& file, InitMethod method, const PoseGraphSolveOptions& options);

/// The usable attempt that stopped at the iteration cap (NO_CONVERGENCE) below every
/// converged chi2, if any converged, solved once more from where it stopped (its
/// iterations and times add up).
void ContinueTheLowestStalled(std::vector<InitAttempt>& attempts, const PoseGraphSolveOptions& options);

/// The requested initial guess solved; for kAuto every one, the chosen one first. Throws
/// InputError (naming `path`) for kFile when the file has no complete guess.
std::vector<InitAttempt> SolveWithInit(const PoseGraphFile& file, InitMethod init, const std::string& path,
                                       const PoseGraphSolveOptions& options);

}  // namespace slambox
