#pragma once
// Sweep results: DIR/results.csv (one row per run and algorithm, deterministic metrics
// only, so a resumed or parallel sweep gives a byte-identical file), DIR/timing.csv
// (run times, which vary between machines and runs), DIR/summary.md (per cell: mean,
// std, median and 95% t-interval over seeds; the best mean per scenario in bold) and the
// regression check against a baseline results.csv.
#include <string>
#include <vector>

#include "app/csv.hpp"
#include "app/sweep_spec.hpp"

namespace slambox {

/// Timing and memory keys vary run to run: kept out of results.csv.
bool IsTimingKey(const std::string& metric_key);

/// Reads every run's metrics.json or failed.json and writes results.csv, timing.csv,
/// summary.md and sweep.json. Runs without a result are listed as missing in summary.md.
void WriteSweepSummary(const std::string& out_dir, const SweepSpec& spec, const std::vector<SweepRun>& runs);

struct CellStats {
  int n = 0;
  double mean = 0, std = 0, median = 0, ci95_low = 0, ci95_high = 0;
};
/// Sample statistics (std with n-1; interval mean ± t(0.975, n-1) std / sqrt(n)).
CellStats Summarize(std::vector<double> values);

struct Regression {
  std::string cell;    ///< "scenario | key=value ... | algorithm"
  std::string metric;
  double baseline_mean = 0, current_mean = 0;
};
/// Cells whose mean error metric (ate_*, rpe_*, landmark_rmse_m) got worse than
/// baseline_mean * (1 + tolerance) + tolerance_abs, plus cells the baseline had but the
/// current results lack (reported with current_mean = NaN).
std::vector<Regression> CheckBaseline(const std::string& results_csv, const std::string& baseline_csv,
                                      double tolerance, double tolerance_abs);

}  // namespace slambox
