#pragma once
// Executes sweep runs in worker processes. Each run is `slambox run ... -o DIR/runs/<id>`
// (done by a forked child of the sweep, or an exec'd worker) in its own process group:
// a crash or a hang (past the timeout) is recorded as DIR/runs/<id>/failed.json and the
// sweep goes on. A run is complete when its
// metrics.json (written last, atomically, by `slambox run`) or failed.json exists, so a
// sweep killed at any moment resumes where it stopped.
#include <functional>
#include <string>
#include <vector>

#include "app/sweep_spec.hpp"

namespace slambox {

/// Called around each fork() by an embedding interpreter (Python's PyOS_BeforeFork,
/// PyOS_AfterFork_Parent, PyOS_AfterFork_Child), so a forked run can call back into it.
struct ForkHooks {
  std::function<void()> before, after_in_parent, after_in_child;
};

struct ExecOptions {
  std::string out_dir;
  /// A program run as `EXE run ...` for each run (a wrapper, or tests' fault injection);
  /// empty: the forked sweep process runs it in-process (no exec).
  std::string worker_exe;
  std::vector<std::string> algorithms;
  /// Module plugins: loaded by the sweep before it forks (its children inherit them),
  /// passed as `--plugin` to an exec'd worker.
  std::vector<std::string> plugins;
  int jobs = 1;
  double timeout_s = 1800.0;
  bool progress_bar = false;  ///< a redrawn bar on a terminal; plain log lines otherwise
  bool quiet = false;
  /// Each run draws the report's pictures of itself (RunRequest::pictures); the renderer
  /// should be loaded before ExecuteRuns, so the forked workers inherit it.
  bool pictures = false;
  ForkHooks fork_hooks;
};

struct ExecSummary {
  int executed = 0;
  int skipped = 0;  ///< already complete (resume)
  int failed = 0;
};

std::string RunDir(const std::string& out_dir, const SweepRun& run);
bool RunComplete(const std::string& out_dir, const SweepRun& run);

ExecSummary ExecuteRuns(const std::vector<SweepRun>& runs, const ExecOptions& options);

}  // namespace slambox
