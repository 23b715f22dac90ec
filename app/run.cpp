#include "app/run.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <cmath>
#include <filesystem>
#include <iostream>

#include "app/registry.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/json_io.hpp"
#include "core/stream_io.hpp"
#include "core/tum.hpp"
#include "core/version.hpp"
#include "eval/evaluate.hpp"
#include "render/figures_run.hpp"
#include "sim/scenario.hpp"
#include "sim/simulate.hpp"

namespace slambox {

namespace fs = std::filesystem;
using nlohmann::json;

Stream LoadOrSimulate(const std::string& input, std::uint64_t seed, bool seed_given,
                      const std::vector<std::string>& scenario_overrides) {
  if (fs::is_regular_file(input) && IsStreamFile(input)) {
    if (seed_given || !scenario_overrides.empty())
      throw InputError(input, 0, "--seed and scenario --set do not apply to a recorded stream",
                       "drop them, or give the scenario instead of the stream");
    return ReadStream(input);
  }
  return Simulate(LoadScenario(input, scenario_overrides), seed);
}

namespace {

double PeakRssMb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;  // Linux reports KiB
}

std::vector<StampedPose> Poses(const Estimate& e) {
  std::vector<StampedPose> out;
  out.reserve(e.trajectory.size());
  for (const auto& p : e.trajectory) out.push_back({p.t_s, p.pose});
  return out;
}

void WriteJson(const fs::path& path, const json& j) { WriteFileAtomic(path.string(), j.dump(1) + "\n"); }

}  // namespace

json RunAndWrite(const RunRequest& request) {
  const Overrides overrides = SplitOverrides(request.sets);
  const Stream stream = LoadOrSimulate(request.input, request.seed, request.seed_given, overrides.scenario);
  const std::vector<std::string> names = ResolveAlgorithms(request.algorithms, stream.header.sensors,
                                                           request.skip_unavailable, HasMap(stream.header.world));
  // Build every module first: a bad --set fails before any file is written.
  std::vector<std::unique_ptr<SlamModule>> modules = CreateModules(names, overrides.algo);

  const bool progress = !request.quiet && isatty(STDERR_FILENO);
  const fs::path dir(request.output_dir);
  const EvalOptions options = RunEvalOptions(stream, request.relations_path);
  fs::create_directories(dir);
  json doc;
  doc["slambox_version"] = kVersion;
  doc["scenario"] = stream.header.scenario_name;
  doc["seed"] = stream.header.seed;
  doc["duration_s"] = stream.header.duration_s;
  doc["distance_m"] = PathLength(stream.groundtruth);
  // A converted log's clock at t = 0 (for `eval --relations ... --time-origin-s`), and the relations used.
  if (stream.header.time_origin_s) doc["time_origin_s"] = *stream.header.time_origin_s;
  if (!request.relations_path.empty()) doc["relations_file"] = request.relations_path;
  doc["algorithms"] = json::object();
  WriteTum((dir / "groundtruth.tum").string(), stream.groundtruth);
  WriteJson(dir / "world.json", {{"scenario", stream.header.scenario_name},
                                 {"seed", stream.header.seed},
                                 {"duration_s", stream.header.duration_s},
                                 {"world", ToJson(stream.header.world)}});

  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string& name = names[i];
    if (progress) std::cerr << "slambox: running " << name << " ..." << std::flush;
    ModuleRun run = ReplayAndScore(*modules[i], stream, options);
    if (run.estimate) {
      try {
        WriteTum((dir / (name + ".tum")).string(), Poses(*run.estimate));
        WriteJson(dir / "estimates" / (name + ".json"), ToJson(*run.estimate));
        WriteJson(dir / "series" / (name + ".json"), ToJson(run.series));
      } catch (const std::exception& e) {  // as a failing module: the others go on
        run.metrics = UnscoredMetrics(RunStatus::kFailed, e.what());
      }
    }
    const Metrics& metrics = run.metrics;
    modules[i].reset();
    doc["algorithms"][name] = ToJson(metrics);
    if (progress) std::cerr << " " << RunStatusName(metrics.status) << "\n";
  }
  doc["peak_rss_mb"] = PeakRssMb();
  WriteJson(dir / "metrics.json", doc);
  if (request.figures) render::RenderRunFigures(dir.string());
  return doc;
}

}  // namespace slambox
