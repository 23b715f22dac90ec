// `slambox sweep SWEEP.yaml -o DIR [-j N] [--resume] [--shard I/N] [--list] [--emit-slurm]
//  [--check BASELINE.csv --tolerance X]` and `slambox sweep --merge DIR`.
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <fstream>
#include <sstream>

#include "app/commands.hpp"
#include "app/sweep_run.hpp"
#include "app/sweep_lock.hpp"
#include "app/sweep_slurm.hpp"
#include "app/sweep_check.hpp"
#include "app/sweep_summary.hpp"
#include "core/error.hpp"

namespace slambox {

namespace fs = std::filesystem;

namespace {

struct SweepArgs {
  std::string sweep_file, out_dir, shard, check, merge_dir, worker_exe, partition, time_limit = "04:00:00";
  int jobs = 0, shards = 8, cpus_per_task = 2;
  double tolerance = 0.10, tolerance_abs = 0.0, timeout_s = 0.0;
  bool resume = false, list = false, emit_slurm = false, figures = true;
  std::vector<std::string> plugins;  ///< --plugin
};

int Check(const SweepArgs& a, const std::string& dir, const SweepSpec& spec) {
  CheckOptions options{.tolerance = {.relative = a.tolerance, .absolute = a.tolerance_abs}};
  for (const auto& [metric, tol] : spec.check_tolerances) options.per_metric[metric] = {tol.first, tol.second};
  const CheckReport report = CheckAgainstBaseline(ReadResultsCsv(dir + "/results.csv"), ReadResultsCsv(a.check), options);
  (report.regressions.empty() ? std::cout : std::cerr) << FormatCheckReport(report, a.check, options);
  return report.regressions.empty() ? 0 : 4;
}

// After the summary is written: what was written, then the regression check.
void Report(const SweepArgs& a, const std::string& dir, const SweepSpec& spec) {
  std::cout << "wrote " << dir << "/results.csv, summary.md" << (a.figures ? ", report.html" : "") << "\n";
  if (!a.check.empty())
    if (const int code = Check(a, dir, spec)) throw CommandExit{code};
}

void Sweep(const SweepArgs& a) {
  if (!a.merge_dir.empty()) {  // rebuild the summary from the shards' run results
    const SweepSpec spec = LoadSweepSpec(a.merge_dir + "/sweep.yaml");
    const SweepLock lock(a.merge_dir, ".lock");
    FinishSweep(a.merge_dir, spec, ExpandSweep(spec), a.figures);
    Report(a, a.merge_dir, spec);
    return;
  }
  if (a.sweep_file.empty()) throw InputError("sweep", 0, "no sweep file given", "slambox sweep SWEEP.yaml -o DIR (or --merge DIR)");
  SweepSpec spec = LoadSweepSpec(a.sweep_file);
  if (a.timeout_s > 0) spec.timeout_s = a.timeout_s;
  std::vector<std::string> plugins = spec.plugins;  // the sweep file's, then --plugin
  for (const auto& p : a.plugins) plugins.push_back(fs::absolute(p).string());
  const std::vector<SweepRun> all = ExpandSweep(spec);
  if (a.list) {
    for (const auto& r : all) {
      std::cout << r.id << "  " << r.scenario << "  seed=" << r.seed;
      for (const auto& s : r.sets) std::cout << "  " << s;
      std::cout << "\n";
    }
    return;
  }
  if (a.out_dir.empty()) throw InputError("sweep", 0, "no output folder", "add -o DIR");
  const std::string exe = fs::read_symlink("/proc/self/exe").string();
  if (a.emit_slurm) {
    fs::create_directories(a.out_dir + "/slurm");
    std::vector<std::string> cli_plugins;
    for (const auto& p : a.plugins) cli_plugins.push_back(fs::absolute(p).string());
    std::cout << SlurmArrayScript({fs::absolute(a.sweep_file).string(), fs::absolute(a.out_dir).string(), exe,
                                   a.shards, a.cpus_per_task, a.time_limit, a.partition, cli_plugins});
    return;
  }
  SweepRunOptions o;
  o.out_dir = a.out_dir;
  o.spec_text = [&] {
    std::stringstream text;
    text << std::ifstream(a.sweep_file).rdbuf();
    return text.str();
  }();
  o.plugins = plugins;
  o.shard = a.shard;
  o.worker_exe = a.worker_exe;
  o.jobs = a.jobs;
  o.resume = a.resume;
  o.figures = a.figures;
  o.progress_bar = isatty(STDERR_FILENO);
  const SweepOutcome outcome = ExecuteSweep(spec, o);
  const ExecSummary& s = outcome.runs;
  std::cout << "sweep: " << s.executed << " runs executed, " << s.skipped << " already done, " << s.failed << " failed\n";
  if (outcome.summary_written) Report(a, a.out_dir, spec);
  else std::cout << "shard done; when every shard is: slambox sweep --merge " << a.out_dir << "\n";
}

}  // namespace

void AddSweepCommand(CLI::App& app) {
  auto a = std::make_shared<SweepArgs>();
  auto* cmd = app.add_subcommand("sweep", "run scenarios x algorithms x parameter grid x seeds in parallel");
  cmd->add_option("sweep_file", a->sweep_file, "sweep YAML (scenarios, algorithms, seeds, grid)");
  cmd->add_option("-o,--output", a->out_dir, "output folder");
  cmd->add_option("--plugin", a->plugins, "load a module plugin for every run (repeatable; also `plugins:` in the file)")
      ->type_name("PATH.so");
  cmd->add_option("-j,--jobs", a->jobs, "worker processes (default: cores)");
  cmd->add_flag("--resume", a->resume, "skip runs that already have a result");
  cmd->add_option("--shard", a->shard, "run only shard I of N (I/N, 0-based), e.g. $SLURM_ARRAY_TASK_ID/8");
  cmd->add_flag("--list", a->list, "print the runs (id, scenario, seed, overrides) and exit");
  cmd->add_option("--merge", a->merge_dir, "build results and summary in DIR from its shards' runs");
  cmd->add_flag("--emit-slurm", a->emit_slurm, "print an sbatch script for a job array of shards");
  cmd->add_option("--shards", a->shards, "array tasks for --emit-slurm")->check(CLI::PositiveNumber);
  cmd->add_option("--cpus-per-task", a->cpus_per_task, "CPUs per array task for --emit-slurm")->check(CLI::PositiveNumber);
  cmd->add_option("--time", a->time_limit, "time limit per array task for --emit-slurm");
  cmd->add_option("--partition", a->partition, "Slurm partition for --emit-slurm");
  cmd->add_option("--check", a->check, "baseline results.csv: exit 4 when a cell's mean error got worse");
  cmd->add_option("--tolerance", a->tolerance, "relative tolerance for --check (0.1 = 10%)")->check(CLI::NonNegativeNumber);
  cmd->add_option("--tolerance-abs", a->tolerance_abs, "absolute tolerance added for --check")->check(CLI::NonNegativeNumber);
  cmd->add_option("--timeout", a->timeout_s, "seconds before a run is killed and recorded failed (overrides timeout_s)");
  cmd->add_flag("--no-figures", [a](std::int64_t) { a->figures = false; }, "skip sweep figures and report");
  cmd->add_option("--worker-exe", a->worker_exe, "program that executes one run (default: this slambox)")
      ->group("");  // for wrappers and tests
  cmd->callback([a] { Sweep(*a); });
}

}  // namespace slambox
