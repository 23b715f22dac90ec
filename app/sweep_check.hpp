#pragma once
// `slambox sweep --check BASELINE.csv`: what got worse against a baseline results.csv.
// Runs are deterministic, so when both tables hold the same seeds every (scenario, grid
// point, seed, module) row is compared with its own baseline row (paired); otherwise the
// cells' means over their ok seeds are compared. Never hidden: a run that was ok and is
// failed/diverged now, a cell with fewer ok runs, a metric that became null, a row or cell
// the baseline had and the results lack. Which metrics are compared and in which
// direction comes from the metric table (eval/metrics.hpp: MetricDescriptor::checked and
// ::better; a checked metric with no better direction, e.g. ANEES, is checked for drift
// either way).
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "eval/results_table.hpp"

namespace slambox {

/// A metric is worse when it moved past |baseline| * relative + absolute in its bad direction.
struct CheckTolerance {
  double relative = 0.10;
  double absolute = 0.0;
};

struct CheckOptions {
  CheckTolerance tolerance;                            ///< every checked metric
  std::map<std::string, CheckTolerance> per_metric;    ///< overrides by metric key
  const CheckTolerance& For(const std::string& metric) const;
};

struct Regression {
  std::string cell;                    ///< CellKey::Text()
  std::optional<std::uint64_t> seed;   ///< paired comparison: the run's seed; cell means: none
  std::string what;                    ///< a metric key, or "status", "ok runs", "row", "cell"
  std::string baseline, current;       ///< the values as text ("ok", "missing", "0.0123", "2/3")
  double change_percent = 0.0;         ///< NaN when not a number
  std::string reproduce;               ///< a `slambox run` command for one run of the cell
};

struct CheckReport {
  bool paired = false;
  int compared = 0;  ///< rows (paired) or cells compared
  std::vector<Regression> regressions;
};

CheckReport CheckAgainstBaseline(const ResultsTable& current, const ResultsTable& baseline, const CheckOptions& options);

/// Human-readable table of the report (what, by how much, the command to reproduce one run).
std::string FormatCheckReport(const CheckReport& report, const std::string& baseline_path, const CheckOptions& options);

}  // namespace slambox
