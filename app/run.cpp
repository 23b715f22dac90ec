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

Overrides SplitOverrides(const std::vector<std::string>& sets) {
  Overrides out;
  for (const auto& s : sets) {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError("--set " + s, 0, "expected KEY=VALUE", "write e.g. --set sensors.lidar.sigma_range_m=0.05");
    const std::string key = s.substr(0, eq);
    if (key.rfind("algo.", 0) == 0) {
      const auto dot = key.find('.', 5);
      if (dot == std::string::npos || dot == 5 || dot + 1 == key.size())
        throw InputError("--set " + s, 0, "an algorithm parameter needs algo.NAME.FIELD",
                         "write e.g. --set algo.fastslam2.particles=200");
      out.algo[key.substr(5, dot - 5)][key.substr(dot + 1)] = s.substr(eq + 1);
    } else {
      out.scenario.push_back(s);
    }
  }
  return out;
}

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

std::vector<std::string> ResolveAlgorithms(const std::vector<std::string>& requested, const SensorSuite& sensors,
                                           bool skip_unavailable, bool has_map) {
  std::vector<std::string> names;
  for (const auto& r : requested) {
    if (r == "all") {
      for (const auto& m : AllModules())
        if (SensorsAllow(m, sensors, has_map)) names.push_back(m.name);
      continue;
    }
    const ModuleInfo& m = FindModule(r);
    if (!SensorsAllow(m, sensors, has_map) && skip_unavailable) continue;
    if (!SensorsAllow(m, sensors))
      throw InputError("--algo " + r, 0, "the stream lacks a sensor '" + r + "' needs",
                       "add the sensor to the scenario or pick another algorithm (see `slambox algorithms`)");
    if (!SensorsAllow(m, sensors, has_map))
      throw InputError("--algo " + r, 0, "'" + r + "' localizes in a known map and the stream's world has no walls",
                       "run it on a scenario (a converted real log carries no map)");
    names.push_back(m.name);  // canonical: exec:PATH/NAME.yaml runs as exec:NAME
  }
  if (names.empty()) throw InputError("--algo", 0, "no algorithm to run", "give --algo NAME[,NAME...] or all");
  return names;
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
                          const std::string& dir, const std::vector<TrajectoryFormat>& formats) {
  const GroundTruth gt{stream.groundtruth, stream.header.world};
  const fs::path d(dir);
  try {
    const Estimate estimate = Replay(module, stream);
    const Evaluation evaluation = EvaluateEstimate(gt, estimate, options);
    const Estimate written = FiniteEstimate(estimate);  // no NaN in a file (diverged says where)
    WriteTum((d / (name + ".tum")).string(), Poses(written));
    if (std::count(formats.begin(), formats.end(), TrajectoryFormat::kKitti))
      WriteKittiPair(d, name, stream.groundtruth, Poses(written));
    WriteJson(d / "estimates" / (name + ".json"), ToJson(written));
    if (written.grid && written.grid->width > 0 && written.grid->height > 0)
      WriteRosMap((d / "maps" / (name + ".yaml")).string(), *written.grid);
    WriteJson(d / "series" / (name + ".json"), ToJson(evaluation.series));
    return evaluation.metrics;
  } catch (const ModuleDiverged& e) {  // e.g. an exec child's NaN pose
    return UnscoredMetrics(RunStatus::kDiverged, e.what());
  } catch (const std::exception& e) {  // a failing module never takes the others down
    return UnscoredMetrics(RunStatus::kFailed, e.what());
  }
}

json RunAndWrite(const RunRequest& request) {
  for (const auto& p : request.plugins) LoadPlugin(p);
  const Overrides overrides = SplitOverrides(request.sets);
  const Stream stream = LoadOrSimulate(request.input, request.seed, request.seed_given, overrides.scenario);
  const World& world = stream.header.world;
  const bool has_map = !world.wall_segments.empty() || !world.wall_circles.empty();
  const std::vector<std::string> names =
      ResolveAlgorithms(request.algorithms, stream.header.sensors, request.skip_unavailable, has_map);
  for (const auto& [name, fields] : overrides.algo) {
    FindModule(name);  // unknown module in --set is an error even when not run
    if (std::find(names.begin(), names.end(), name) == names.end())
      throw InputError("--set algo." + name, 0, "'" + name + "' is not among the algorithms run",
                       "add it to --algo or drop the --set");
  }
  // Build every module first: a bad --set fails before any file is written.
  std::vector<std::unique_ptr<SlamModule>> modules;
  for (const auto& name : names)
    modules.push_back(FindModule(name).create(overrides.algo.count(name) ? overrides.algo.at(name) : ParamOverrides{}));

  const bool progress = !request.quiet && isatty(STDERR_FILENO);
  const fs::path dir(request.output_dir);
  EvalOptions options;
  // With unknown ids a module's landmark ids are its own indices: match by assignment.
  const auto& lm = stream.header.sensors.landmarks;
  options.landmarks.matching = lm && lm->known_ids ? LandmarkMatching::kById : LandmarkMatching::kOptimal;
  if (!request.relations_path.empty()) {
    options.relations = ReadRelations(request.relations_path);
    options.relation_matching.time_origin_s = stream.header.time_origin_s.value_or(0.0);
    if (RelationsWithin(options.relations, stream.header.duration_s, options.relation_matching) == 0)
      throw InputError(request.relations_path, 0,
                       "no relation falls within the stream's time span (time origin " +
                           std::to_string(options.relation_matching.time_origin_s) + " s, " +
                           std::to_string(stream.header.duration_s) + " s long)",
                       stream.header.time_origin_s ? "give the relations file of this log"
                                                   : "the stream records no time origin: re-convert the log with "
                                                     "`slambox convert carmen LOG -o STREAM`");
  }
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
  if (const OccupancyGrid truth = TrueOccupancyGrid(world); truth.width > 0)
    WriteRosMap((dir / "maps" / "groundtruth.yaml").string(), truth);

  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string& name = names[i];
    if (progress) std::cerr << "slambox: running " << name << " ..." << std::flush;
    const Metrics metrics = RunModuleAndWrite(*modules[i], name, stream, options, dir.string(), request.formats);
    modules[i].reset();
    doc["algorithms"][name] = ToJson(metrics);
    if (progress) std::cerr << " " << RunStatusName(metrics.status) << "\n";
  }
  doc["peak_rss_mb"] = PeakRssMb();
  WriteJson(dir / "metrics.json", doc);
  if (request.figures) Render().run_figures(dir.string());
  return doc;
}

}  // namespace slambox
