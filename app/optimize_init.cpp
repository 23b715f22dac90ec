#include "app/optimize_init.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "slam/pose_graph_graduated.hpp"
#include "slam/pose_graph_init.hpp"

namespace slambox {
namespace {

// `auto` keeps the attempt that converged to the lowest objective (robust_chi2_final: with a
// kernel, the non-robust chi2 of a solution that rejected the outliers counts them in full);
// usable before not usable, converged before stalled; within 1e-6 relative (Ceres' default
// function_tolerance, at which each solve stops: the same optimum) the earlier attempt wins
// (file, lago, chordal, odometry; a guess's plain solve before its graduated one).
bool Better(const InitAttempt& a, const InitAttempt& b) {
  const auto rank = [](const PoseGraphSolveResult& r) { return (r.usable ? 2 : 0) + (r.termination == "CONVERGENCE"); };
  if (rank(a.result) != rank(b.result)) return rank(a.result) > rank(b.result);
  return a.result.robust_chi2_final < b.result.robust_chi2_final * (1.0 - 1e-6);
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

namespace {

// The graph with `method`'s initial guess (landmarks, but for kFile, at the mean of their
// observations from the initialized poses); the guess's time in *init_time_s.
PoseGraph InitialGuess(const PoseGraphFile& file, InitMethod method, double* init_time_s) {
  PoseGraph g = file.graph;
  const auto t0 = std::chrono::steady_clock::now();
  if (method == InitMethod::kOdometry) g.poses = SpanningTreeInitialization(g);
  if (method == InitMethod::kLago) g.poses = LagoInitialization(g);
  if (method == InitMethod::kChordal) g.poses = ChordalInitialization(g);
  // The pose-only initializers leave landmarks to their observations at the new poses:
  // the mean over them (cityTrees10000 from the odometry chain: chi2 8668.929 in 56
  // iterations; from the first observation alone 8668.934 in 27, ATE 0.977 m vs 0.936 m).
  if (method != InitMethod::kFile) g.landmarks = LandmarksFromObservations(g, g.poses);
  *init_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return g;
}

// Two guesses within 1 um and 1 urad everywhere (a file whose VERTEX lines are its odometry
// chain, printed to 6 decimals) lead to the same optimum: the second is not solved.
bool SameGuess(const PoseGraph& a, const PoseGraph& b) {
  for (size_t i = 0; i < a.poses.size(); ++i)
    if (std::abs(a.poses[i].x - b.poses[i].x) > 1e-6 || std::abs(a.poses[i].y - b.poses[i].y) > 1e-6 ||
        std::abs(NormalizeAngle(a.poses[i].theta - b.poses[i].theta)) > 1e-6)
      return false;
  for (size_t j = 0; j < a.landmarks.size(); ++j)
    if ((a.landmarks[j] - b.landmarks[j]).cwiseAbs().maxCoeff() > 1e-6) return false;
  return true;
}

// LAGO's and chordal's guesses are solved from every edge, outliers included, so a schedule
// that starts nearly quadratic from them only keeps the outliers' pull.
bool Chained(InitMethod method) { return method == InitMethod::kOdometry || method == InitMethod::kFile; }

std::vector<InitAttempt> SolveGuess(PoseGraph guess, InitMethod method, double init_time_s,
                                    const PoseGraphSolveOptions& options, bool graduate) {
  InitAttempt a{method, init_time_s, std::move(guess), {}};
  std::vector<InitAttempt> out;
  if (graduate && GraduatedDecades(a.graph, options) > 0) {  // the same guess graduated, before the plain solve moves it
    InitAttempt g = a;
    const GraduatedSolveResult r = SolvePoseGraphGraduated(g.graph, options);
    g.result = r.result;
    g.robust_stages = r.stages;
    out.push_back(std::move(g));
  }
  a.result = SolvePoseGraph(a.graph, options);
  out.insert(out.begin(), std::move(a));  // plain first: it wins ties
  return out;
}

}  // namespace

std::vector<InitAttempt> SolveFrom(const PoseGraphFile& file, InitMethod method, const PoseGraphSolveOptions& options) {
  double init_time_s = 0.0;
  PoseGraph guess = InitialGuess(file, method, &init_time_s);
  return SolveGuess(std::move(guess), method, init_time_s, options, Chained(method));
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
    if (a.result.usable && a.result.termination == "CONVERGENCE")
      converged = std::min(converged, a.result.robust_chi2_final);
  InitAttempt* lowest = nullptr;
  for (InitAttempt& a : attempts)
    if (a.result.usable && a.result.termination == "NO_CONVERGENCE" &&
        a.result.robust_chi2_final < converged * (1.0 - 1e-6) &&
        (lowest == nullptr || a.result.robust_chi2_final < lowest->result.robust_chi2_final))
      lowest = &a;
  if (lowest == nullptr || !std::isfinite(converged)) return;  // none converged: the lowest is kept anyway
  const PoseGraphSolveResult more = SolvePoseGraph(lowest->graph, options);  // in place: from where it stopped
  PoseGraphSolveResult& r = lowest->result;
  r.chi2_final = more.chi2_final, r.robust_chi2_final = more.robust_chi2_final;
  r.iterations += more.iterations, r.time_s += more.time_s;
  r.termination = more.termination, r.usable = more.usable, r.edge_weights = more.edge_weights;
}

// The requested initial guess solved (plainly, and graduated where SolveFrom says); for
// `auto` every cheap one (the file's guess, LAGO, chordal, the odometry chain: milliseconds
// each); the best kept and the others listed.
std::vector<InitAttempt> SolveWithInit(const PoseGraphFile& file, InitMethod init, const std::string& path,
                                       const PoseGraphSolveOptions& options) {
  if (init == InitMethod::kFile && !file.has_initial_guess)
    throw InputError(path, 0,
                     "--init file, but not every pose and landmark has a VERTEX_SE2 / VERTEX2 / VERTEX_XY line",
                     "use --init lago (or odometry) to compute an initial guess");
  struct Guess {
    InitMethod method;
    PoseGraph graph;
    double init_time_s = 0.0;
  };
  std::vector<Guess> guesses;
  for (const InitMethod method : {InitMethod::kFile, InitMethod::kLago, InitMethod::kChordal, InitMethod::kOdometry}) {
    if (init != InitMethod::kAuto && method != init) continue;
    if (method == InitMethod::kFile && !file.has_initial_guess) continue;
    Guess g{method, {}, 0.0};
    g.graph = InitialGuess(file, method, &g.init_time_s);
    if (std::none_of(guesses.begin(), guesses.end(), [&](const Guess& h) { return SameGuess(h.graph, g.graph); }))
      guesses.push_back(std::move(g));
  }
  // One graduated attempt (costly on big graphs: city10000 + 1000 outliers, 6 solves of up
  // to 11000 loop closures): from the chained guess with the lower chi2.
  const Guess* graduate = nullptr;
  for (const Guess& g : guesses)
    if (Chained(g.method) && (graduate == nullptr || Chi2(g.graph) < Chi2(graduate->graph))) graduate = &g;
  std::vector<InitAttempt> attempts;
  for (Guess& g : guesses)
    for (InitAttempt& a : SolveGuess(std::move(g.graph), g.method, g.init_time_s, options, &g == graduate))
      attempts.push_back(std::move(a));
  ContinueTheLowestStalled(attempts, options);
  size_t best = 0;
  for (size_t i = 1; i < attempts.size(); ++i)
    if (Better(attempts[i], attempts[best])) best = i;
  std::rotate(attempts.begin(), attempts.begin() + static_cast<long>(best), attempts.begin() + static_cast<long>(best) + 1);
  return attempts;  // the chosen one first
}

}  // namespace slambox
