#pragma once
// `slambox run`: load or simulate one stream, replay it to each requested module, score
// each estimate and write the run folder:
//   DIR/metrics.json, DIR/groundtruth.tum, DIR/<algo>.tum, DIR/world.json,
//   DIR/estimates/<algo>.json, DIR/series/<algo>.json, DIR/figures/
// A module that throws or diverges is recorded with its status; the others go on.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/run_modules.hpp"
#include "core/stream.hpp"

namespace slambox {

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

}  // namespace slambox
