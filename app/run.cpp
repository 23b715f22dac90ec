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
#include "app/render_library.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/file_status.hpp"
#include "core/finite_estimate.hpp"
#include "core/json_io.hpp"
#include "core/ros_map.hpp"
#include "core/stream_io.hpp"
#include "core/tum.hpp"
#include "core/version.hpp"
#include "eval/association.hpp"
#include "eval/evaluate.hpp"
#include "eval/grid_map.hpp"
#include "sim/scenario.hpp"
#include "sim/simulate.hpp"

namespace slambox {

namespace fs = std::filesystem;
using nlohmann::json;

Stream LoadOrSimulate(const std::string& input, std::uint64_t seed, bool seed_given,
                      const std::vector<std::string>& scenario_overrides) {
  if (IsRegularFile(input) && IsStreamFile(input)) {
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

// KITTI files have no timestamps: write the matched pairs, line by line.
void WriteKittiPair(const fs::path& dir, const std::string& name, const std::vector<StampedPose>& groundtruth,
                    const std::vector<StampedPose>& estimate) {
  if (groundtruth.empty()) {
    WriteKittiPoses((dir / (name + ".kitti")).string(), estimate);
    return;
  }
  const Association a = Associate(groundtruth, estimate);
  std::vector<StampedPose> gt, est;
  for (size_t k = 0; k < a.t_s.size(); ++k) {
    gt.push_back({a.t_s[k], a.groundtruth[k]});
    est.push_back({a.t_s[k], a.estimate[k]});
  }
  WriteKittiPoses((dir / (name + ".kitti")).string(), est);
  WriteKittiPoses((dir / (name + ".groundtruth.kitti")).string(), gt);
}

}  // namespace

Metrics RunModuleAndWrite(SlamModule& module, const std::string& name, const Stream& stream, const EvalOptions& options,
                          const std::string& dir, const std::vector<TrajectoryFormat>& formats,
                          std::optional<Estimate>* kept, const std::vector<std::vector<int>>* true_observation_ids) {
  ModuleRun run = ReplayAndScore(module, stream, options, true_observation_ids);
  if (!run.estimate) return run.metrics;
  const fs::path d(dir);
  try {
    Estimate written = FiniteEstimate(*run.estimate);  // no NaN in a file (diverged says where)
    WriteTum((d / (name + ".tum")).string(), Poses(written));
    if (std::count(formats.begin(), formats.end(), TrajectoryFormat::kKitti))
      WriteKittiPair(d, name, stream.groundtruth, Poses(written));
    WriteJson(d / "estimates" / (name + ".json"), ToJson(written));
    if (written.grid && written.grid->width > 0 && written.grid->height > 0)
      WriteRosMap((d / "maps" / (name + ".yaml")).string(), *written.grid);
    WriteJson(d / "series" / (name + ".json"), ToJson(run.series));
    if (kept) *kept = std::move(written);
  } catch (const std::exception& e) {  // as a failing module: the others go on
    run.metrics = UnscoredMetrics(RunStatus::kFailed, e.what());
  }
  return run.metrics;
}

json RunAndWrite(const RunRequest& request) {
  for (const auto& p : request.plugins) LoadPlugin(p);
  const Overrides overrides = SplitOverrides(request.sets);
  Stream stream = LoadOrSimulate(request.input, request.seed, request.seed_given, overrides.scenario);
  std::optional<std::vector<std::vector<int>>> hidden_ids;
  if (request.hide_landmark_ids) hidden_ids = HideLandmarkIds(stream);
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
  doc["converted_log"] = IsConvertedLog(stream.header);  // a log: its seed means nothing
  doc["duration_s"] = stream.header.duration_s;
  doc["distance_m"] = GroundTruthDistance(stream.groundtruth);  // NaN -> null: a log's is unknown
  // A converted log's clock at t = 0 (for `eval --relations ... --time-origin-s`), and the relations used.
  if (stream.header.time_origin_s) doc["time_origin_s"] = *stream.header.time_origin_s;
  if (!request.relations_path.empty()) doc["relations_file"] = request.relations_path;
  if (request.hide_landmark_ids) doc["landmark_ids_hidden"] = true;
  doc["algorithms"] = json::object();
  // What the registry says of each module (ModuleInfo), e.g. which are baselines: the
  // figures style those by this flag, never by a name.
  doc["modules"] = json::object();
  for (const auto& name : names) doc["modules"][name] = {{"baseline", FindModule(name).baseline}};
  // The sweep report's pictures are drawn from this run in memory, after metrics.json.
  render::RunFolder pictures;
  if (request.pictures) pictures = render::RunFolderOfStream(stream, dir.string());
  WriteTum((dir / "groundtruth.tum").string(), stream.groundtruth);
  WriteJson(dir / "world.json", {{"scenario", stream.header.scenario_name},
                                 {"seed", stream.header.seed},
                                 {"duration_s", stream.header.duration_s},
                                 {"world", ToJson(stream.header.world)}});
  if (const OccupancyGrid truth = TrueOccupancyGrid(stream.header.world); truth.width > 0)
    WriteRosMap((dir / "maps" / "groundtruth.yaml").string(), truth);

  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string& name = names[i];
    if (progress) std::cerr << "slambox: running " << name << " ..." << std::flush;
    std::optional<Estimate> estimate;
    const Metrics metrics = RunModuleAndWrite(*modules[i], name, stream, options, dir.string(), request.formats,
                                              request.pictures ? &estimate : nullptr,
                                              hidden_ids ? &*hidden_ids : nullptr);
    modules[i].reset();
    doc["algorithms"][name] = ToJson(metrics);
    if (request.pictures) {
      render::AlgorithmResult a{.name = name, .metrics = metrics, .trajectory = {}, .estimate = std::move(estimate),
                                .series = std::nullopt, .baseline = FindModule(name).baseline};
      if (a.estimate) a.trajectory = Poses(*a.estimate);
      pictures.algorithms.push_back(std::move(a));
    }
    if (progress) std::cerr << " " << RunStatusName(metrics.status) << "\n";
  }
  doc["peak_rss_mb"] = PeakRssMb();
  WriteJson(dir / "metrics.json", doc);
  if (request.figures) Render().run_figures(dir.string());
  if (request.pictures) {
    // metrics.json's order (the run folder's, so colours match the run's own figures).
    std::sort(pictures.algorithms.begin(), pictures.algorithms.end(),
              [](const auto& a, const auto& b) { return a.name < b.name; });
    pictures.metrics = doc;
    try {
      Render().run_pictures(pictures, dir.string());
    } catch (const std::exception& e) {  // the run's results stand; the report says a picture is missing
      std::cerr << "slambox: warning: no pictures for " << dir.string() << ": " << e.what() << "\n";
    }
  }
  return doc;
}

}  // namespace slambox
