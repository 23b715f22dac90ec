#pragma once
// A whole sweep, as `slambox sweep SWEEP.yaml -o DIR` does it and `slambox.sweep()` (Python)
// reuses: validate every scenario variant and module once, lock DIR, refuse a folder that
// already holds results unless resuming, write DIR/sweep.yaml + sweep.json, fork the runs
// (app/sweep_exec), then write results.csv, timing.csv, summary.md (and figures).
#include <string>
#include <vector>

#include "app/sweep_exec.hpp"
#include "app/sweep_spec.hpp"

namespace slambox {

struct SweepRunOptions {
  std::string out_dir;
  std::string spec_text;              ///< written as DIR/sweep.yaml (what `sweep --merge` reads back)
  std::vector<std::string> plugins;   ///< module plugins (absolute), loaded before the workers fork
  std::string shard;                  ///< "I/N": only runs with index % N == I; empty: every run
  std::string worker_exe;             ///< see ExecOptions
  int jobs = 0;                       ///< worker processes; 0: one per core
  bool resume = false;                ///< skip complete runs instead of refusing the folder
  bool figures = true;                ///< sweep figures and report.html (the renderer library)
  bool progress_bar = false;
  bool quiet = false;                 ///< no per-run log lines
  ForkHooks fork_hooks;               ///< see ExecOptions
};

struct SweepOutcome {
  ExecSummary runs;
  bool summary_written = false;  ///< false for a shard: `sweep --merge` writes it when all are done
};

/// Throws InputError (file, line, fix) for a bad scenario, module, option or relations file
/// before any run starts, or when DIR is locked by another sweep or already holds results.
SweepOutcome ExecuteSweep(const SweepSpec& spec, const SweepRunOptions& options);

/// Writes results.csv, timing.csv, summary.md from DIR/runs (and figures + report.html).
void FinishSweep(const std::string& dir, const SweepSpec& spec, const std::vector<SweepRun>& runs, bool figures);

/// "I/N" -> (I, N); throws InputError unless 0 <= I < N.
void ParseShard(const std::string& text, std::size_t& index, std::size_t& count);

}  // namespace slambox
