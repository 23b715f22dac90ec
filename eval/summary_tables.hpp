#pragma once
// The tables of a sweep's summary.md and report, from results.csv's rows: per scenario one
// Markdown table of mean ± std over seeds (3 significant digits, the unit in the header,
// `2/3 ok` where runs failed or diverged, the best mean in bold, columns without any value
// left out) and a second table, collapsed (<details>), of medians and 95 % intervals of
// the mean (eval/statistics.hpp, IntervalOfMean). Cells are padded so the file reads as
// plain text too.
#include <string>
#include <vector>

#include "eval/results_table.hpp"
#include "eval/statistics.hpp"

namespace slambox {

/// "3.49 ± 1.20", "0.00628 ± 0.00007": the mean to 3 significant digits, the std to the
/// same decimals (to 2 significant digits when those would show 0).
std::string FormatMeanStd(double mean, double std);

/// One sentence saying what a cell and the interval are, for the top of summary.md.
std::string SummaryCaption(IntervalMethod interval);

/// The section of `scenario`: "## scenario", the mean ± std table, the collapsed table.
/// Rows in order of first appearance in `table` (cell = scenario, grid point, algorithm).
std::string ScenarioSummary(const ResultsTable& table, const std::string& scenario, IntervalMethod interval);

/// Scenarios in order of first appearance.
std::vector<std::string> ScenariosOf(const ResultsTable& table);

}  // namespace slambox
