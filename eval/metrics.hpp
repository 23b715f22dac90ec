#pragma once
// One module's scores as a typed record (one algorithm's entry of metrics.json) and the
// table of metric descriptors that every writer and reader of metrics goes through: the
// metrics.json serializer, results.csv, summary.md, `sweep --check`, the run report and
// the sweep figures. The keys are the schema; eval/README.md lists them.
// Adding a metric = one field here + one row in MetricTable() (eval/metrics.cpp).
#include <array>
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "eval/relation_metric.hpp"
#include "eval/statistics.hpp"

namespace slambox {

enum class RunStatus { kOk, kDiverged, kFailed };

/// Real metrics are NaN when they do not apply (written as null); counts that may not
/// apply are optional. Strings that are empty are left out of metrics.json.
struct Metrics {
  RunStatus status = RunStatus::kOk;
  std::string reason;  ///< why diverged / failed
  std::string note;    ///< e.g. a stream without ground truth
  /// False for a module that threw before it could be scored: only status and reason exist.
  bool scored = true;

  std::optional<std::int64_t> matched_poses;
  double distance_m = NAN;  ///< [m] ground-truth path length

  // NaN statistics until computed (ComputeStatistics of nothing).
  ErrorStatistics ate = ComputeStatistics({});          ///< [m] translation error, no alignment
  ErrorStatistics ate_aligned = ComputeStatistics({});  ///< [m] after SE(2) Umeyama
  ErrorStatistics heading = ComputeStatistics({});      ///< [deg]
  bool alignment_valid = false;
  std::optional<std::array<double, 3>> alignment_se2;  ///< T_gt_est [x_m, y_m, theta_deg]
  std::string alignment_reason;                        ///< when not valid

  ErrorStatistics rpe_trans = ComputeStatistics({});  ///< [m]
  ErrorStatistics rpe_rot = ComputeStatistics({});    ///< [deg]
  std::optional<std::int64_t> rpe_pairs;
  double rpe_delta = NAN;
  std::string rpe_delta_unit;
  bool rpe_all_pairs = false;

  RelationMetric relation = ComputeRelationMetric({}, {});  ///< the RPE pairs', or a relations file's
  std::optional<std::int64_t> relation_unmatched;            ///< relations of the file left out; null without one
  std::optional<std::int64_t> kitti_segments;
  double kitti_trans_percent = NAN, kitti_rot_deg_per_m = NAN;

  double anees = NAN;
  std::optional<std::int64_t> nees_steps;
  double nees_in_band_fraction = NAN;

  double landmark_rmse_m = NAN, landmark_ospa_m = NAN, landmark_anees = NAN;
  std::optional<std::int64_t> landmark_spurious, landmark_missed, landmark_matched;
  std::optional<std::string> landmark_matching;  ///< "id" or "optimal"; null without a map

  /// eval/association_agreement.hpp; null without true ids or without the module's assignments.
  double association_agreement = NAN;
  std::optional<std::int64_t> association_duplicates, association_misses, association_unused;

  double grid_cell_error = NAN;
  std::optional<std::int64_t> grid_known_cells;
  double grid_mean_nearest_occupied_m = NAN, grid_mean_truth_to_estimate_m = NAN;

  std::optional<std::int64_t> loop_closures, loop_closures_proposed, revisit_episodes;
  double loop_closure_precision = NAN, loop_closure_recall = NAN;

  double runtime_s = NAN, realtime_factor = NAN;
  double step_time_median_s = NAN, step_time_p95_s = NAN, step_time_max_s = NAN;
};

/// The entry of a module that could not be scored (it threw, or its run failed).
Metrics UnscoredMetrics(RunStatus status, std::string reason = "");
const char* RunStatusName(RunStatus status);

enum class Better { kLower, kHigher, kNeither };

/// Where a metric's value lives in Metrics. A string that is empty is left out of the
/// file (reason, note); an optional string that is empty is written as null.
using MetricField = std::variant<double*, int*, std::optional<std::int64_t>*, bool*, std::string*,
                                 std::optional<std::string>*, std::optional<std::array<double, 3>>*, RunStatus*>;

struct MetricDescriptor {
  std::string key;    ///< metrics.json key = results.csv column
  std::string label;  ///< table header and figure axis, unit included: "ATE RMSE [m]"
  std::string unit;   ///< "m", "deg", "m2", "%", "s", "" (a count or a ratio)
  Better better = Better::kNeither;
  bool evo = false;            ///< evo computes the same number (README, "Metrics and their evo equivalents")
  int summary_column = -1;     ///< column of summary.md (0, 1, ...); -1: not shown there
  bool headline = false;       ///< a column of the run report's headline table (table order)
  bool checked = false;        ///< compared with the baseline by `sweep --check`
  bool timing = false;         ///< varies run to run: timing.csv instead of results.csv
  std::function<MetricField(Metrics&)> field;
};

/// Every key of an algorithm's metrics.json entry, in the run report's column order.
const std::vector<MetricDescriptor>& MetricTable();
/// nullptr for a key that is not a metric (grid columns, unknown keys).
const MetricDescriptor* FindMetric(const std::string& key);
/// The summary.md columns, in order.
std::vector<const MetricDescriptor*> SummaryMetrics();

/// The value as metrics.json holds it: a number, null, a string, a bool or an array;
/// a discarded value (json::value_t::discarded) for a key left out of the file (an empty
/// string; everything but status and reason of an entry that was not scored).
nlohmann::json MetricValue(const MetricDescriptor& d, const Metrics& m);
/// A number for results.csv and the sweep statistics: NaN for null or a non-number.
double MetricNumber(const MetricDescriptor& d, const Metrics& m);

/// One algorithm's entry of metrics.json (keys sorted, as nlohmann::json stores them).
nlohmann::json ToJson(const Metrics& m);
/// Reads an entry back; unknown keys are ignored (a newer writer), a wrong type throws
/// InputError naming `path` and the key.
Metrics MetricsFromJson(const nlohmann::json& entry, const std::string& path);

}  // namespace slambox
