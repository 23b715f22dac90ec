#include "app/optimize_init.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "slam/pose_graph_init.hpp"

namespace slambox {
namespace {

// `auto` keeps the attempt that converged to the lowest chi2 (usable before not usable,
// converged before stalled); within 1e-6 relative (Ceres' default function_tolerance, at
// which each solve stops: the same optimum) the earlier of file, lago, chordal, odometry wins.
bool Better(const InitAttempt& a, const InitAttempt& b) {
  const auto rank = [](const PoseGraphSolveResult& r) { return (r.usable ? 2 : 0) + (r.termination == "CONVERGENCE"); };
  if (rank(a.result) != rank(b.result)) return rank(a.result) > rank(b.result);
  return a.result.chi2_final < b.result.chi2_final * (1.0 - 1e-6);
}

}  // namespace

const std::map<std::string, InitMethod>& InitMethodNames() {
  static const std::map<std::string, InitMethod> kNames = {{"auto", InitMethod::kAuto},
                                                           {"file", InitMethod::kFile},
                                                           {"lago", InitMethod::kLago},
                                                           {"chordal", InitMethod::kChordal},
                                                           {"odometry", InitMethod::kOdometry}};
  return kNames;
}

std::string InitName(InitMethod m) {
  for (const auto& [name, method] : InitMethodNames())
    if (method == m) return name;
  return "?";
}

InitAttempt SolveFrom(const PoseGraphFile& file, InitMethod method, const PoseGraphSolveOptions& options) {
  InitAttempt a{method, 0.0, file.graph, {}};
  const auto t0 = std::chrono::steady_clock::now();
  if (method == InitMethod::kOdometry) a.graph.poses = SpanningTreeInitialization(a.graph);
  if (method == InitMethod::kLago) a.graph.poses = LagoInitialization(a.graph);
  if (method == InitMethod::kChordal) a.graph.poses = ChordalInitialization(a.graph);
  // The pose-only initializers leave landmarks to their observations at the new poses:
  // the mean over them (cityTrees10000 from the odometry chain: chi2 8668.929 in 56
  // iterations; from the first observation alone 8668.934 in 27, ATE 0.977 m vs 0.936 m).
  if (method != InitMethod::kFile) a.graph.landmarks = LandmarksFromObservations(a.graph, a.graph.poses);
  a.init_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  a.result = SolvePoseGraph(a.graph, options);
  return a;
}

// An attempt stopped by the iteration cap below every converged chi2 is still descending
// toward a lower optimum than theirs (measured: the chordal guess on manhattan with
// 0.3 rad of extra rotation noise on every edge is at chi2 603732 after the cap of 100
// iterations and converges to 603569 after 106, where LAGO's converged at 995628): the
// lowest such attempt is continued once from where it stopped, with the same cap (so
// `--max-iterations` is per solve).
void ContinueTheLowestStalled(std::vector<InitAttempt>& attempts, const PoseGraphSolveOptions& options) {
  double converged = std::numeric_limits<double>::infinity();
  for (const InitAttempt& a : attempts)
    if (a.result.usable && a.result.termination == "CONVERGENCE") converged = std::min(converged, a.result.chi2_final);
  InitAttempt* lowest = nullptr;
  for (InitAttempt& a : attempts)
    if (a.result.usable && a.result.termination == "NO_CONVERGENCE" && a.result.chi2_final < converged * (1.0 - 1e-6) &&
        (lowest == nullptr || a.result.chi2_final < lowest->result.chi2_final))
      lowest = &a;
  if (lowest == nullptr || !std::isfinite(converged)) return;  // none converged: the lowest is kept anyway
  const PoseGraphSolveResult more = SolvePoseGraph(lowest->graph, options);  // in place: from where it stopped
  PoseGraphSolveResult& r = lowest->result;
  r.chi2_final = more.chi2_final, r.iterations += more.iterations, r.time_s += more.time_s;
  r.termination = more.termination, r.usable = more.usable, r.edge_weights = more.edge_weights;
}

// The requested initial guess solved; for `auto` every cheap one (the file's guess, LAGO,
// chordal, the odometry chain: milliseconds each), the best kept and the others listed.
std::vector<InitAttempt> SolveWithInit(const PoseGraphFile& file, InitMethod init, const std::string& path,
                                       const PoseGraphSolveOptions& options) {
  if (init == InitMethod::kFile && !file.has_initial_guess)
    throw InputError(path, 0,
                     "--init file, but not every pose and landmark has a VERTEX_SE2 / VERTEX2 / VERTEX_XY line",
                     "use --init lago (or odometry) to compute an initial guess");
  if (init != InitMethod::kAuto) return {SolveFrom(file, init, options)};
  std::vector<InitAttempt> attempts;
  for (const InitMethod method : {InitMethod::kFile, InitMethod::kLago, InitMethod::kChordal, InitMethod::kOdometry})
    if (method != InitMethod::kFile || file.has_initial_guess) attempts.push_back(SolveFrom(file, method, options));
  ContinueTheLowestStalled(attempts, options);
  size_t best = 0;
  for (size_t i = 1; i < attempts.size(); ++i)
    if (Better(attempts[i], attempts[best])) best = i;
  std::rotate(attempts.begin(), attempts.begin() + static_cast<long>(best), attempts.begin() + static_cast<long>(best) + 1);
  return attempts;  // the chosen one first
}

}  // namespace slambox
