#pragma once
// Sweep results: DIR/results.csv (one row per run and algorithm, deterministic metrics
// only, so a resumed or parallel sweep gives a byte-identical file), DIR/timing.csv
// (run times, which vary between machines and runs), DIR/summary.md (per cell: mean ±
// std over seeds, the best mean per scenario in bold; medians and 95 % intervals in a
// collapsed table: eval/summary_tables). The table itself is eval/results_table; the
// regression check is app/sweep_check.
#include <string>
#include <vector>

#include "app/sweep_spec.hpp"
#include "eval/results_table.hpp"

namespace slambox {

/// Reads every run's metrics.json or failed.json and writes results.csv, timing.csv and
/// summary.md, the summary from the same in-memory rows as results.csv. Runs without a
/// result are listed as missing in summary.md.
void WriteSweepSummary(const std::string& out_dir, const SweepSpec& spec, const std::vector<SweepRun>& runs);

/// summary.md's text for `table` (rows of `spec`'s runs; `missing` runs have no result).
std::string SummaryMarkdown(const ResultsTable& table, const SweepSpec& spec, std::size_t runs, int missing);


}  // namespace slambox
