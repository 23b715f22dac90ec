#include "app/sweep_run.hpp"

#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>
#include <thread>

#include "app/registry.hpp"
#include "app/render_library.hpp"
#include "app/run.hpp"
#include "app/sweep_lock.hpp"
#include "app/sweep_summary.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/stream_io.hpp"
#include "eval/relations.hpp"
#include "sim/scenario.hpp"

namespace slambox {

namespace fs = std::filesystem;

void ParseShard(const std::string& text, std::size_t& index, std::size_t& count) {
  const auto slash = text.find('/');
  try {
    if (slash == std::string::npos) throw std::invalid_argument("no slash");
    index = std::stoul(text.substr(0, slash));
    count = std::stoul(text.substr(slash + 1));
  } catch (const std::exception&) {
    count = 0;
  }
  if (count == 0 || index >= count)
    throw InputError("--shard " + text, 0, "expected I/N with 0 <= I < N", "write e.g. --shard 0/4 (Slurm: $SLURM_ARRAY_TASK_ID/N)");
}

namespace {

// Loads every distinct scenario variant and builds every module with its parameters once,
// so a typo fails the sweep before any run starts instead of failing every run.
void Validate(const SweepSpec& spec, const std::vector<SweepRun>& runs) {
  std::set<std::string> seen;
  for (const auto& run : runs) {
    std::string key = run.scenario;
    for (const auto& s : run.sets) key += "\n" + s;
    if (!seen.insert(key).second) continue;
    const Overrides o = SplitOverrides(run.sets);
    // A stream (e.g. a converted log) has its sensors in its header; a scenario in its file.
    const SensorSuite sensors =
        run.is_stream ? ReadStreamHeader(run.scenario).sensors : LoadScenario(run.scenario, o.scenario).sensors;
    ResolveAlgorithms(spec.algorithms, sensors, /*skip_unavailable=*/true);  // throws if none applies
    if (!run.relations.empty()) ReadRelations(run.relations);  // a malformed file fails before any run
    for (const auto& [name, params] : o.algo) FindModule(name).create(params);
  }
}

void WriteManifest(const std::string& dir, const SweepSpec& spec) {
  nlohmann::json grid = nlohmann::json::object();
  for (const auto& [k, v] : spec.grid) grid[k] = v;
  // Which modules are baselines (ModuleInfo::baseline): the figures style them by this flag.
  nlohmann::json modules = nlohmann::json::object();
  for (const auto& name : spec.algorithms) {
    if (name == "all") {
      for (const auto& m : AllModules())  // what `all` runs: not the named-only peers
        if (m.in_all) modules[m.name] = {{"baseline", m.baseline}};
    } else {
      const ModuleInfo& m = FindModule(name);  // by its own name (exec:PATH.yaml runs as exec:STEM)
      modules[m.name] = {{"baseline", m.baseline}};
    }
  }
  const nlohmann::json manifest = {{"scenarios", spec.scenarios}, {"algorithms", spec.algorithms},
                                   {"seeds", spec.seeds},         {"grid", grid},
                                   {"interval", IntervalMethodName(spec.interval)}, {"modules", modules}};
  WriteFileAtomic(dir + "/sweep.json", manifest.dump(1) + "\n");
}

}  // namespace

void FinishSweep(const std::string& dir, const SweepSpec& spec, const std::vector<SweepRun>& runs, bool figures) {
  WriteSweepSummary(dir, spec, runs);
  if (figures) {
    Render().sweep_figures(dir);
    Render().write_report(dir);
  }
}

SweepOutcome ExecuteSweep(const SweepSpec& spec, const SweepRunOptions& a) {
  if (a.out_dir.empty()) throw InputError("sweep", 0, "no output folder", "add -o DIR");
  const std::vector<SweepRun> all = ExpandSweep(spec);
  for (const auto& p : a.plugins) LoadPlugin(p);  // before the workers fork: they inherit the modules
  Validate(spec, all);
  std::vector<SweepRun> mine = all;
  std::string lock_name = ".lock";
  if (!a.shard.empty()) {
    std::size_t index = 0, count = 0;
    ParseShard(a.shard, index, count);
    lock_name = ".lock.shard-" + std::to_string(index) + "-of-" + std::to_string(count);
    mine.clear();
    for (const auto& r : all)
      if (r.index % count == index) mine.push_back(r);
  }
  // Before looking at what is done: a running sweep's half-done folder is not "done".
  const SweepLock lock(a.out_dir, lock_name);
  if (!a.resume)
    for (const auto& r : mine)
      if (RunComplete(a.out_dir, r))
        throw InputError(a.out_dir, 0, "the folder already holds results of this sweep",
                         "add --resume to continue it, or give a new -o folder");
  fs::create_directories(a.out_dir);
  WriteFileAtomic(a.out_dir + "/sweep.yaml", a.spec_text);
  WriteManifest(a.out_dir, spec);
  ExecOptions o;
  o.out_dir = a.out_dir;
  o.worker_exe = a.worker_exe;
  o.algorithms = spec.algorithms;
  o.plugins = a.plugins;
  o.jobs = a.jobs > 0 ? a.jobs : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  o.timeout_s = spec.timeout_s;
  o.progress_bar = a.progress_bar;
  o.quiet = a.quiet;
  o.fork_hooks = a.fork_hooks;
  o.pictures = a.figures;
  if (o.pictures) Render();  // loaded once here: the forked workers inherit it
  SweepOutcome outcome;
  outcome.runs = ExecuteRuns(mine, o);
  if (a.shard.empty()) {
    FinishSweep(a.out_dir, spec, all, a.figures);
    outcome.summary_written = true;
  }
  return outcome;
}

}  // namespace slambox
