#pragma once
// `slambox run`: load or simulate one stream, replay it to each requested module, score
// each estimate and write the run folder:
//   DIR/metrics.json, DIR/groundtruth.tum, DIR/<algo>.tum, DIR/world.json,
//   DIR/estimates/<algo>.json, DIR/series/<algo>.json, DIR/figures/
// A module that throws or diverges is recorded with its status; the others go on.
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/params.hpp"
#include "core/stream.hpp"

namespace slambox {

/// `--set` arguments split by destination: scenario keys, and `algo.NAME.FIELD` keys.
struct Overrides {
  std::vector<std::string> scenario;              ///< "dotted.key=value"
  std::map<std::string, ParamOverrides> algo;     ///< module name -> FIELD -> value
};
/// Throws InputError for an argument without '=' or an `algo.` key without a field.
Overrides SplitOverrides(const std::vector<std::string>& sets);

/// A built-in scenario name, a scenario file, or a stream file (then `seed` and scenario
/// overrides must be absent: a stream is already simulated).
Stream LoadOrSimulate(const std::string& input, std::uint64_t seed, bool seed_given,
                      const std::vector<std::string>& scenario_overrides);

struct RunRequest {
  std::string input;
  std::uint64_t seed = 0;
  bool seed_given = false;
  std::vector<std::string> sets;        ///< raw `--set k=v` arguments
  std::vector<std::string> algorithms;  ///< names, or {"all"}
  std::string output_dir;
  bool figures = true;
  bool quiet = false;  ///< no progress lines on stderr
  bool skip_unavailable = false;  ///< skip named modules whose sensors the stream lacks
  /// Kümmerle relations file (the log's clock, mapped by the stream's time origin): when
  /// given, relation_* score every module on it.
  std::string relations_path;
};

/// Runs and writes the run folder; returns the metrics.json document.
nlohmann::json RunAndWrite(const RunRequest& request);

/// Module names for `--algo`: "all" expands to every module the sensors allow. A named
/// module the sensors do not allow is an error, or skipped with `skip_unavailable` (sweeps
/// list modules once for scenarios with different sensors).
std::vector<std::string> ResolveAlgorithms(const std::vector<std::string>& requested, const SensorSuite& sensors,
                                           bool skip_unavailable = false, bool has_map = true);

}  // namespace slambox
