#pragma once
// Reads a run folder written by `slambox run` (layout fixed in DESIGN.md): metrics,
// ground truth, each module's trajectory, estimate and error series, through the same
// readers the writers pair with (eval/metrics, eval/error_series, core/json_io, core/tum). Missing optional
// files leave their fields empty; figures that need them are skipped.
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/estimate.hpp"
#include "core/stream.hpp"
#include "core/world.hpp"
#include "eval/error_series.hpp"
#include "eval/metrics.hpp"

namespace slambox::render {

struct AlgorithmResult {
  std::string name;
  Metrics metrics;                       ///< its entry in metrics.json
  std::vector<StampedPose> trajectory;   ///< <algo>.tum (empty when missing)
  std::optional<Estimate> estimate;      ///< estimates/<algo>.json
  std::optional<ErrorSeries> series;     ///< series/<algo>.json
};

struct RunFolder {
  std::string dir;
  std::string scenario;
  long seed = 0;
  nlohmann::json metrics;
  World world;
  bool has_world = false;
  std::vector<StampedPose> groundtruth;
  std::vector<AlgorithmResult> algorithms;  ///< metrics.json order
};

/// Throws InputError when metrics.json is missing or any present file is malformed.
RunFolder ReadRunFolder(const std::string& dir);

}  // namespace slambox::render
