#include "app/run_modules.hpp"

#include <algorithm>

#include "app/registry.hpp"
#include "core/error.hpp"

namespace slambox {

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

std::vector<std::string> ResolveAlgorithms(const std::vector<std::string>& requested, const SensorSuite& sensors,
                                           bool skip_unavailable, bool has_map) {
  std::vector<std::string> names;
  for (const auto& r : requested) {
    if (r == "all") {
      for (const auto& m : AllModules())  // expensive peers (in_all = false) only when named
        if (m.in_all && SensorsAllow(m, sensors, has_map)) names.push_back(m.name);
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

bool HasMap(const World& world) { return !world.wall_segments.empty() || !world.wall_circles.empty(); }

std::vector<std::unique_ptr<SlamModule>> CreateModules(const std::vector<std::string>& names,
                                                       const std::map<std::string, ParamOverrides>& algo) {
  for (const auto& [name, fields] : algo) {
    FindModule(name);  // unknown module in --set is an error even when not run
    if (std::find(names.begin(), names.end(), name) == names.end())
      throw InputError("--set algo." + name, 0, "'" + name + "' is not among the algorithms run",
                       "add it to --algo or drop the --set");
  }
  std::vector<std::unique_ptr<SlamModule>> modules;
  for (const auto& name : names)
    modules.push_back(FindModule(name).create(algo.count(name) ? algo.at(name) : ParamOverrides{}));
  return modules;
}

EvalOptions RunEvalOptions(const Stream& stream, const std::string& relations_path) {
  EvalOptions options;
  // With unknown ids a module's landmark ids are its own indices: match by assignment.
  const auto& lm = stream.header.sensors.landmarks;
  options.landmarks.matching = lm && lm->known_ids ? LandmarkMatching::kById : LandmarkMatching::kOptimal;
  if (!relations_path.empty()) {
    options.relations = ReadRelations(relations_path);
    options.relation_matching.time_origin_s = stream.header.time_origin_s.value_or(0.0);
    if (RelationsWithin(options.relations, stream.header.duration_s, options.relation_matching) == 0)
      throw InputError(relations_path, 0,
                       "no relation falls within the stream's time span (time origin " +
                           std::to_string(options.relation_matching.time_origin_s) + " s, " +
                           std::to_string(stream.header.duration_s) + " s long)",
                       stream.header.time_origin_s ? "give the relations file of this log"
                                                   : "the stream records no time origin: re-convert the log with "
                                                     "`slambox convert carmen LOG -o STREAM`");
  }
  return options;
}

std::vector<std::vector<int>> HideLandmarkIds(Stream& stream) {
  std::vector<std::vector<int>> ids = ObservationIds(stream);
  for (SensorEvent& e : stream.events)
    if (auto* l = std::get_if<LandmarkEvent>(&e))
      for (LandmarkObservation& o : l->observations) o.id = -1;
  if (stream.header.sensors.landmarks) stream.header.sensors.landmarks->known_ids = false;
  return ids;
}

ModuleRun ReplayAndScore(SlamModule& module, const Stream& stream, const EvalOptions& options,
                         const std::vector<std::vector<int>>* true_observation_ids) {
  ModuleRun run;
  try {
    Estimate estimate = Replay(module, stream);
    const GroundTruth truth{stream.groundtruth, stream.header.world,
                            true_observation_ids ? *true_observation_ids : ObservationIds(stream)};
    Evaluation evaluation = EvaluateEstimate(truth, estimate, options);
    run.metrics = std::move(evaluation.metrics);
    run.series = std::move(evaluation.series);
    run.estimate = std::move(estimate);
  } catch (const ModuleDiverged& e) {  // e.g. an exec child's NaN pose
    run.metrics = UnscoredMetrics(RunStatus::kDiverged, e.what());
  } catch (const std::exception& e) {  // a failing module never takes the others down
    run.metrics = UnscoredMetrics(RunStatus::kFailed, e.what());
  }
  return run;
}

}  // namespace slambox
