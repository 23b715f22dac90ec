#include "eval/metrics.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace slambox {

namespace {

template <auto Member>
MetricField Of(Metrics& m) {
  return &(m.*Member);
}
template <auto Outer, auto Inner>
MetricField In(Metrics& m) {
  return &((m.*Outer).*Inner);
}

class TableBuilder {
 public:
  MetricDescriptor& Add(std::string key, std::string label, std::string unit, Better better,
                        std::function<MetricField(Metrics&)> field) {
    rows_.push_back({.key = std::move(key), .label = std::move(label), .unit = std::move(unit), .better = better,
                     .field = std::move(field)});
    return rows_.back();
  }
  /// prefix_{rmse,mean,median,std,min,max}<unit> and prefix_sse<unit>2 of one ErrorStatistics
  /// (evo's statistics); `name` starts the labels, `rmse_label` is the RMSE's own.
  template <auto Group>
  void AddStatistics(const std::string& prefix, const std::string& name, const std::string& rmse_label,
                     const std::string& unit, bool evo, bool checked) {
    auto add = [&](const std::string& stat, const std::string& label, const std::string& u, auto field) {
      MetricDescriptor& d = Add(prefix + "_" + stat + "_" + u, label, u, Better::kLower, field);
      d.evo = evo;
      d.checked = checked && stat != "min";  // the smallest error says nothing of a regression
    };
    add("rmse", rmse_label, unit, In<Group, &ErrorStatistics::rmse>);
    add("mean", name + " mean [" + unit + "]", unit, In<Group, &ErrorStatistics::mean>);
    add("median", name + " median [" + unit + "]", unit, In<Group, &ErrorStatistics::median>);
    add("std", name + " std [" + unit + "]", unit, In<Group, &ErrorStatistics::std>);
    add("min", name + " min [" + unit + "]", unit, In<Group, &ErrorStatistics::min>);
    add("max", name + " max [" + unit + "]", unit, In<Group, &ErrorStatistics::max>);
    add("sse", name + " SSE [" + unit + "2]", unit + "2", In<Group, &ErrorStatistics::sse>);
  }
  std::vector<MetricDescriptor> rows_;
};

std::vector<MetricDescriptor> BuildTable() {
  TableBuilder t;
  const Better lower = Better::kLower, higher = Better::kHigher, neither = Better::kNeither;
  // The run report's headline columns first, in its order; summary.md's columns numbered.
  t.Add("status", "status", "", neither, Of<&Metrics::status>);
  t.AddStatistics<&Metrics::ate>("ate", "ATE", "ATE RMSE [m]", "m", true, true);
  t.AddStatistics<&Metrics::ate_aligned>("ate_aligned", "aligned ATE", "aligned ATE [m]", "m", true, true);
  t.AddStatistics<&Metrics::rpe_trans>("rpe_trans", "RPE trans", "RPE trans [m]", "m", true, true);
  t.AddStatistics<&Metrics::rpe_rot>("rpe_rot", "RPE rot", "RPE rot [deg]", "deg", true, true);
  // ANEES has no better direction: --check flags a drift either way.
  t.Add("anees", "ANEES", "", neither, Of<&Metrics::anees>).checked = true;
  t.Add("landmark_rmse_m", "landmarks [m]", "m", lower, Of<&Metrics::landmark_rmse_m>).checked = true;
  t.Add("loop_closures", "loop closures", "", neither, Of<&Metrics::loop_closures>);
  t.Add("loop_closure_precision", "loop closure precision", "", higher, Of<&Metrics::loop_closure_precision>);
  t.Add("runtime_s", "runtime [s]", "s", lower, Of<&Metrics::runtime_s>).timing = true;
  t.Add("realtime_factor", "real-time factor", "", higher, Of<&Metrics::realtime_factor>).timing = true;
  for (const char* k : {"status", "ate_rmse_m", "ate_mean_m", "ate_max_m", "ate_aligned_rmse_m", "rpe_trans_rmse_m",
                        "rpe_rot_rmse_deg", "anees", "landmark_rmse_m", "loop_closures", "loop_closure_precision",
                        "runtime_s", "realtime_factor"})
    std::find_if(t.rows_.begin(), t.rows_.end(), [&](const auto& d) { return d.key == k; })->headline = true;
  int column = 0;
  for (const char* k : {"ate_rmse_m", "ate_aligned_rmse_m", "rpe_trans_rmse_m", "rpe_rot_rmse_deg", "landmark_rmse_m",
                        "anees"})
    std::find_if(t.rows_.begin(), t.rows_.end(), [&](const auto& d) { return d.key == k; })->summary_column = column++;

  // Everything else (the report lists these alphabetically).
  t.Add("reason", "reason", "", neither, Of<&Metrics::reason>);
  t.Add("note", "note", "", neither, Of<&Metrics::note>);
  t.Add("matched_poses", "matched poses", "", neither, Of<&Metrics::matched_poses>);
  t.Add("distance_m", "distance [m]", "m", neither, Of<&Metrics::distance_m>);
  t.AddStatistics<&Metrics::heading>("heading", "heading", "heading RMSE [deg]", "deg", true, false);
  t.Add("alignment_valid", "alignment valid", "", neither, Of<&Metrics::alignment_valid>);
  t.Add("alignment_se2", "alignment [m, m, deg]", "", neither, Of<&Metrics::alignment_se2>);
  t.Add("alignment_reason", "alignment reason", "", neither, Of<&Metrics::alignment_reason>);
  t.Add("rpe_pairs", "RPE pairs", "", neither, Of<&Metrics::rpe_pairs>);
  t.Add("rpe_delta", "RPE delta", "", neither, Of<&Metrics::rpe_delta>);
  t.Add("rpe_delta_unit", "RPE delta unit", "", neither, Of<&Metrics::rpe_delta_unit>);
  t.Add("rpe_all_pairs", "RPE all pairs", "", neither, Of<&Metrics::rpe_all_pairs>);
  t.Add("relation_count", "relations", "", neither, In<&Metrics::relation, &RelationMetric::relations>);
  t.Add("relation_unmatched", "unmatched relations", "", neither, Of<&Metrics::relation_unmatched>);
  t.Add("relation_trans_mean_m", "relation trans mean [m]", "m", lower,
        In<&Metrics::relation, &RelationMetric::trans_mean_m>).checked = true;
  t.Add("relation_trans_std_m", "relation trans std [m]", "m", lower,
        In<&Metrics::relation, &RelationMetric::trans_std_m>);
  t.Add("relation_trans_sq_mean_m2", "relation trans² mean [m2]", "m2", lower,
        In<&Metrics::relation, &RelationMetric::trans_sq_mean_m2>);
  t.Add("relation_trans_sq_std_m2", "relation trans² std [m2]", "m2", lower,
        In<&Metrics::relation, &RelationMetric::trans_sq_std_m2>);
  t.Add("relation_rot_mean_deg", "relation rot mean [deg]", "deg", lower,
        In<&Metrics::relation, &RelationMetric::rot_mean_deg>).checked = true;
  t.Add("relation_rot_std_deg", "relation rot std [deg]", "deg", lower,
        In<&Metrics::relation, &RelationMetric::rot_std_deg>);
  t.Add("relation_rot_sq_mean_deg2", "relation rot² mean [deg2]", "deg2", lower,
        In<&Metrics::relation, &RelationMetric::rot_sq_mean_deg2>);
  t.Add("relation_rot_sq_std_deg2", "relation rot² std [deg2]", "deg2", lower,
        In<&Metrics::relation, &RelationMetric::rot_sq_std_deg2>);
  t.Add("kitti_segments", "KITTI segments", "", neither, Of<&Metrics::kitti_segments>);
  t.Add("kitti_trans_percent", "KITTI translation [%]", "%", lower, Of<&Metrics::kitti_trans_percent>);
  t.Add("kitti_rot_deg_per_m", "KITTI rotation [deg/m]", "deg/m", lower, Of<&Metrics::kitti_rot_deg_per_m>);
  t.Add("nees_steps", "NEES steps", "", neither, Of<&Metrics::nees_steps>);
  t.Add("nees_in_band_fraction", "NEES in 95% band", "", neither, Of<&Metrics::nees_in_band_fraction>);
  t.Add("landmark_ospa_m", "landmark OSPA [m]", "m", lower, Of<&Metrics::landmark_ospa_m>);
  t.Add("landmark_anees", "landmark ANEES", "", neither, Of<&Metrics::landmark_anees>);
  t.Add("landmark_spurious", "spurious landmarks", "", lower, Of<&Metrics::landmark_spurious>).checked = true;
  t.Add("landmark_missed", "missed landmarks", "", lower, Of<&Metrics::landmark_missed>);
  t.Add("landmark_matched", "matched landmarks", "", higher, Of<&Metrics::landmark_matched>);
  t.Add("landmark_matching", "landmark matching", "", neither, Of<&Metrics::landmark_matching>);
  t.Add("association_agreement", "association agreement", "", higher, Of<&Metrics::association_agreement>);
  t.Add("association_duplicates", "association duplicates", "", lower, Of<&Metrics::association_duplicates>);
  t.Add("association_misses", "association misses", "", lower, Of<&Metrics::association_misses>);
  t.Add("association_unused", "association unused observations", "", lower, Of<&Metrics::association_unused>);
  t.Add("grid_cell_error", "grid cell error", "", lower, Of<&Metrics::grid_cell_error>);
  t.Add("grid_known_cells", "grid known cells", "", neither, Of<&Metrics::grid_known_cells>);
  t.Add("grid_mean_nearest_occupied_m", "grid estimate→truth [m]", "m", lower,
        Of<&Metrics::grid_mean_nearest_occupied_m>);
  t.Add("grid_mean_truth_to_estimate_m", "grid truth→estimate [m]", "m", lower,
        Of<&Metrics::grid_mean_truth_to_estimate_m>);
  t.Add("loop_closures_proposed", "loop closures proposed", "", neither, Of<&Metrics::loop_closures_proposed>);
  t.Add("loop_closure_recall", "loop closure recall", "", higher, Of<&Metrics::loop_closure_recall>);
  t.Add("revisit_episodes", "revisit episodes", "", neither, Of<&Metrics::revisit_episodes>);
  t.Add("step_time_median_s", "step time median [s]", "s", lower, Of<&Metrics::step_time_median_s>).timing = true;
  t.Add("step_time_p95_s", "step time p95 [s]", "s", lower, Of<&Metrics::step_time_p95_s>).timing = true;
  t.Add("step_time_max_s", "step time max [s]", "s", lower, Of<&Metrics::step_time_max_s>).timing = true;
  return t.rows_;
}

using nlohmann::json;

template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;  // C++20 deduces it; clang 14 (the fuzz build) needs the guide

[[noreturn]] void WrongType(const std::string& path, const std::string& key, const char* expected) {
  throw InputError(path, 0, "metric '" + key + "' is not " + expected, "re-run the command that wrote the file");
}

}  // namespace

Metrics UnscoredMetrics(RunStatus status, std::string reason) {
  Metrics m;
  m.status = status;
  m.reason = std::move(reason);
  m.scored = false;
  return m;
}

const char* RunStatusName(RunStatus s) {
  return s == RunStatus::kOk ? "ok" : s == RunStatus::kDiverged ? "diverged" : "failed";
}

const std::vector<MetricDescriptor>& MetricTable() {
  static const std::vector<MetricDescriptor> table = BuildTable();
  return table;
}

const MetricDescriptor* FindMetric(const std::string& key) {
  const auto& t = MetricTable();
  const auto it = std::find_if(t.begin(), t.end(), [&](const MetricDescriptor& d) { return d.key == key; });
  return it == t.end() ? nullptr : &*it;
}

std::vector<const MetricDescriptor*> SummaryMetrics() {
  std::vector<const MetricDescriptor*> out;
  for (const auto& d : MetricTable())
    if (d.summary_column >= 0) out.push_back(&d);
  std::sort(out.begin(), out.end(), [](auto* a, auto* b) { return a->summary_column < b->summary_column; });
  return out;
}

json MetricValue(const MetricDescriptor& d, const Metrics& m) {
  if (!m.scored && d.key != "status" && d.key != "reason") return json(json::value_t::discarded);
  // The field accessor only takes an address; nothing is written through it here.
  const MetricField f = d.field(const_cast<Metrics&>(m));
  return std::visit(
      Overloaded{[](double* v) { return NumberOrNull(*v); },
                 [](int* v) { return json(*v); },
                 [](std::optional<std::int64_t>* v) { return *v ? json(**v) : json(nullptr); },
                 [](bool* v) { return json(*v); },
                 [](std::string* v) { return v->empty() ? json(json::value_t::discarded) : json(*v); },
                 [](std::optional<std::string>* v) { return *v ? json(**v) : json(nullptr); },
                 [](std::optional<std::array<double, 3>>* v) { return *v ? json(**v) : json(nullptr); },
                 [](RunStatus* v) { return json(RunStatusName(*v)); }},
      f);
}

double MetricNumber(const MetricDescriptor& d, const Metrics& m) {
  const json v = MetricValue(d, m);
  return v.is_number() ? v.get<double>() : NAN;
}

json ToJson(const Metrics& m) {
  json out = json::object();
  for (const auto& d : MetricTable()) {
    json v = MetricValue(d, m);
    if (!v.is_discarded()) out[d.key] = std::move(v);
  }
  return out;
}

Metrics MetricsFromJson(const json& entry, const std::string& path) {
  if (!entry.is_object()) throw InputError(path, 0, "an algorithm's metrics are not an object", "re-run `slambox run`");
  Metrics m;
  m.scored = false;
  for (const auto& item : entry.items()) {
    // Not a structured binding: the lambdas below capture them, which clang 14 refuses.
    const std::string& key = item.key();
    const json& value = item.value();
    const MetricDescriptor* d = FindMetric(key);
    if (!d) continue;  // a key this version does not know
    if (key != "status" && key != "reason") m.scored = true;
    const bool null = value.is_null();
    std::visit(Overloaded{[&](double* v) {
                            if (!null && !value.is_number()) WrongType(path, key, "a number");
                            *v = null ? NAN : value.get<double>();
                          },
                          [&](int* v) {
                            if (!value.is_number_integer()) WrongType(path, key, "an integer");
                            *v = value.get<int>();
                          },
                          [&](std::optional<std::int64_t>* v) {
                            if (!null && !value.is_number_integer()) WrongType(path, key, "an integer");
                            if (null) v->reset();
                            else *v = value.get<std::int64_t>();
                          },
                          [&](bool* v) {
                            if (!value.is_boolean()) WrongType(path, key, "true or false");
                            *v = value.get<bool>();
                          },
                          [&](std::string* v) {
                            if (!value.is_string()) WrongType(path, key, "a string");
                            *v = value.get<std::string>();
                          },
                          [&](std::optional<std::string>* v) {
                            if (!null && !value.is_string()) WrongType(path, key, "a string");
                            if (null) v->reset();
                            else *v = value.get<std::string>();
                          },
                          [&](std::optional<std::array<double, 3>>* v) {
                            if (null) return v->reset();
                            if (!value.is_array() || value.size() != 3) WrongType(path, key, "[x_m, y_m, theta_deg]");
                            *v = std::array<double, 3>{};
                            for (int i = 0; i < 3; ++i) (**v)[i] = value[i].is_number() ? value[i].get<double>() : NAN;
                          },
                          [&](RunStatus* v) {
                            const std::string s = value.is_string() ? value.get<std::string>() : "";
                            if (s != "ok" && s != "diverged" && s != "failed") WrongType(path, key, "ok, diverged or failed");
                            *v = s == "ok" ? RunStatus::kOk : s == "diverged" ? RunStatus::kDiverged : RunStatus::kFailed;
                          }},
               d->field(m));
  }
  return m;
}

}  // namespace slambox
