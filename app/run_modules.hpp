#pragma once
// The part of `slambox run` that the Python module shares with the CLI (python/): which
// modules to run, building them with their `algo.NAME.FIELD` overrides, the evaluation
// options a stream implies, and one module's replay and score. Writes no file.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/estimate.hpp"
#include "core/params.hpp"
#include "core/slam_module.hpp"
#include "core/stream.hpp"
#include "eval/evaluate.hpp"

namespace slambox {

/// `--set` arguments split by destination: scenario keys, and `algo.NAME.FIELD` keys.
struct Overrides {
  std::vector<std::string> scenario;              ///< "dotted.key=value"
  std::map<std::string, ParamOverrides> algo;     ///< module name -> FIELD -> value
};
/// Throws InputError for an argument without '=' or an `algo.` key without a field.
Overrides SplitOverrides(const std::vector<std::string>& sets);

/// Module names for `--algo`: "all" expands to every module the sensors allow. A named
/// module the sensors do not allow is an error, or skipped with `skip_unavailable` (sweeps
/// list modules once for scenarios with different sensors).
std::vector<std::string> ResolveAlgorithms(const std::vector<std::string>& requested, const SensorSuite& sensors,
                                           bool skip_unavailable = false, bool has_map = true);

/// True when the world has walls (a known map, for localization modules).
bool HasMap(const World& world);

/// Builds the registry modules `names` (in order) with their overrides. An override for a
/// module not among `names` is an InputError, as is a bad value: nothing has run yet.
std::vector<std::unique_ptr<SlamModule>> CreateModules(const std::vector<std::string>& names,
                                                       const std::map<std::string, ParamOverrides>& algo);

/// The evaluation options `slambox run` uses on `stream`: landmarks matched by id when the
/// detector knows ids (else by assignment); relation_* on `relations_path` when not empty
/// (an InputError when no relation falls within the stream).
EvalOptions RunEvalOptions(const Stream& stream, const std::string& relations_path);

/// One module's outcome: metrics.json's entry; the estimate and error series unless it failed.
struct ModuleRun {
  Metrics metrics;
  std::optional<Estimate> estimate;
  ErrorSeries series;
};

/// Replays `stream` to `module` and scores it. A module that throws gives status failed
/// with what() as the reason and no estimate; it never takes others down.
/// Association is scored against `true_observation_ids` (ObservationIds' layout), or the
/// stream's own ids when null.
ModuleRun ReplayAndScore(SlamModule& module, const Stream& stream, const EvalOptions& options,
                         const std::vector<std::vector<int>>* true_observation_ids = nullptr);

/// `run --hide-landmark-ids`: every observation's id becomes -1 and the detector reports
/// unknown ids, so modules associate by themselves (a real log's ids, e.g. Victoria
/// Park's, stay as the truth association_agreement scores against). Returns the ids hidden.
std::vector<std::vector<int>> HideLandmarkIds(Stream& stream);

}  // namespace slambox
