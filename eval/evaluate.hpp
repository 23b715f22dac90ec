#pragma once
// The evaluator's entry point: one SLAM module's Estimate against ground truth -> its
// Metrics (eval/metrics.hpp: one algorithm's entry of metrics.json, NaN/null where not
// applicable) and the per-step ErrorSeries the figure renderer plots.
// The keys and their evo equivalents are the schema in eval/README.md.
#include <vector>

#include "core/estimate.hpp"
#include "core/stream.hpp"
#include "core/world.hpp"
#include "eval/divergence.hpp"
#include "eval/error_series.hpp"
#include "eval/grid_map.hpp"
#include "eval/kitti_segments.hpp"
#include "eval/landmark_map.hpp"
#include "eval/loop_closures.hpp"
#include "eval/metrics.hpp"
#include "eval/relations.hpp"
#include "eval/rpe.hpp"

namespace slambox {

struct GroundTruth {
  std::vector<StampedPose> trajectory;  ///< time-ordered
  World world;
  /// The true id of each observation of each landmark event (-1: none, e.g. clutter or a
  /// detector without ids); empty: association is not scored.
  std::vector<std::vector<int>> observation_ids;
};

/// Per landmark event of the stream, the ids its observations carry (ObservationIds of a
/// stream whose detector knows ids is the truth association_agreement scores against).
std::vector<std::vector<int>> ObservationIds(const Stream& stream);

enum class AlignMode { kNone, kSE2, kOrigin };

struct EvalOptions {
  double max_time_diff_s = 0.01;   ///< [s] association tolerance (evo --t_max_diff)
  bool interpolate_groundtruth = false;  ///< linear interpolation instead of nearest stamp
  /// Alignment applied before ate_* (DESIGN: none; the estimate starts at the true start).
  /// ate_aligned_* always use SE(2) Umeyama.
  AlignMode align = AlignMode::kNone;
  RpeOptions rpe;                  ///< default: delta 1 m, consecutive pairs (evo's rules)
  KittiOptions kitti;
  LandmarkMapOptions landmarks;    ///< matching, OSPA cutoff 1 m, order 2
  GridMapOptions grid;
  LoopClosureOptions loop_closures;  ///< 0.2 m / 2 deg
  DivergenceOptions divergence;
  double nees_confidence = 0.95;   ///< two-sided band for per-step pose NEES (d = 3, one run)
  /// Kümmerle relations (a relations file): when given, relation_* score the estimate on
  /// them (no ground truth needed); else relation_* use the RPE pairs as relations.
  std::vector<Relation> relations;
  RelationMatchOptions relation_matching;
};

struct Evaluation {
  Metrics metrics;     ///< one algorithm's entry of metrics.json (ToJson)
  ErrorSeries series;  ///< series/<algo>.json (ToJson)
};

Evaluation EvaluateEstimate(const GroundTruth& gt, const Estimate& est, const EvalOptions& options = {});

/// Length of the polyline through the positions [m].
double PathLength(const std::vector<StampedPose>& trajectory);

/// The distance travelled by the ground truth [m]; NaN (written as null) when the stream
/// has none (a converted log): 0 m would claim the robot stood still.
double GroundTruthDistance(const std::vector<StampedPose>& groundtruth);

}  // namespace slambox
