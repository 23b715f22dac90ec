#pragma once
// `slambox run`: load or simulate one stream, replay it to each requested module, score
// each estimate and write the run folder:
//   DIR/metrics.json, DIR/groundtruth.tum, DIR/<algo>.tum, DIR/world.json,
//   DIR/estimates/<algo>.json, DIR/series/<algo>.json, DIR/figures/,
//   DIR/maps/<algo>.yaml + .pgm (ROS map_server format) for every module that builds a
//   grid, and DIR/maps/groundtruth.yaml + .pgm (the walls rasterized at 0.05 m);
//   with `kitti` among the formats also DIR/<algo>.kitti and DIR/<algo>.groundtruth.kitti:
//   the estimate's poses matched to ground truth (as eval matches them) and the matching
//   true poses, line by line (`evo_ape kitti`); all estimate poses without ground truth.
// A module that throws or diverges is recorded with its status; the others go on.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/run_modules.hpp"
#include "core/kitti_poses.hpp"
#include "core/stream.hpp"
#include "eval/evaluate.hpp"

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
  std::vector<std::string> plugins;     ///< module plugins to load first (`--plugin PATH.so`)
  std::string output_dir;
  bool figures = true;
  /// The sweep report's pictures (DIR/pictures/, render/run_pictures.hpp), drawn from the
  /// run in memory after metrics.json is written; a drawing error is a warning.
  bool pictures = false;
  bool quiet = false;  ///< no progress lines on stderr
  bool skip_unavailable = false;  ///< skip named modules whose sensors the stream lacks
  /// Trajectory files besides the TUM ones (always written, DESIGN.md).
  std::vector<TrajectoryFormat> formats = {TrajectoryFormat::kTum};
  /// Kümmerle relations file (the log's clock, mapped by the stream's time origin): when
  /// given, relation_* score every module on it.
  std::string relations_path;
  /// Strip the landmark ids before the modules see the stream (HideLandmarkIds); they
  /// stay the truth of association_agreement.
  bool hide_landmark_ids = false;
};

/// Replays `stream` to `module`, scores it and writes DIR/NAME.tum, DIR/estimates/NAME.json
/// (both of FiniteEstimate: no NaN in a file), DIR/series/NAME.json, DIR/maps/NAME.yaml for a
/// grid and the `formats`' files; returns its metrics (status ok, diverged or failed with a
/// reason). Never throws. With `kept`, the estimate as written (FiniteEstimate) is moved there.
Metrics RunModuleAndWrite(SlamModule& module, const std::string& name, const Stream& stream,
                          const EvalOptions& options, const std::string& dir,
                          const std::vector<TrajectoryFormat>& formats = {TrajectoryFormat::kTum},
                          std::optional<Estimate>* kept = nullptr,
                          const std::vector<std::vector<int>>* true_observation_ids = nullptr);

/// Runs and writes the run folder; returns the metrics.json document.
nlohmann::json RunAndWrite(const RunRequest& request);

}  // namespace slambox
