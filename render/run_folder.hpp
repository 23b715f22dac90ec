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
  bool baseline = false;                 ///< metrics.json's modules.<algo>.baseline (ModuleInfo::baseline)
};

struct RunFolder {
  std::string dir;
  std::string scenario;
  long seed = 0;
  bool converted_log = false;  ///< metrics.json's converted_log (older folders: true when there is no ground truth)
  nlohmann::json metrics;
  World world;
  bool has_world = false;
  std::vector<StampedPose> groundtruth;
  std::vector<AlgorithmResult> algorithms;  ///< metrics.json order
};

/// False for a converted real log's empty world: nothing true to draw.
inline bool WorldHasGeometry(const World& w) {
  return !w.wall_segments.empty() || !w.wall_circles.empty() || !w.landmarks.empty() || !w.movers.empty();
}

/// `doc.modules.NAME.baseline` of a metrics.json or sweep.json (false when absent: the
/// flag, never the name, makes a baseline); InputError naming `path` when not a bool.
bool BaselineFlag(const nlohmann::json& doc, const std::string& name, const std::string& path);

/// Throws InputError when metrics.json is missing or any present file is malformed.
RunFolder ReadRunFolder(const std::string& dir);

/// What ReadRunFolder reads back of a run of `stream` before any module's results (dir,
/// scenario, seed, converted_log, world, ground truth), from the stream itself: the sweep
/// draws its pictures from this, in memory. Leaves metrics empty. Inline: the app links no
/// renderer (it loads it at run time) but fills this.
inline RunFolder RunFolderOfStream(const Stream& stream, const std::string& dir) {
  RunFolder run;
  run.dir = dir;
  run.scenario = stream.header.scenario_name;
  run.seed = static_cast<long>(stream.header.seed);
  run.converted_log = IsConvertedLog(stream.header);
  run.world = stream.header.world;
  run.has_world = WorldHasGeometry(stream.header.world);
  run.groundtruth = stream.groundtruth;
  return run;
}

}  // namespace slambox::render
