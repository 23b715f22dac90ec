#pragma once
// results.csv of a sweep: one row per run and algorithm, the fixed columns, the swept
// keys (dotted scenario/algorithm keys) and the deterministic metrics (eval/metrics.hpp
// keys). Written and read here only: the sweep summary, `sweep --merge`, `sweep --check`
// and the sweep figures all go through ReadResultsCsv / ResultsCsv.
#include <compare>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace slambox {

using GridValues = std::vector<std::pair<std::string, std::string>>;  ///< swept key -> value, column order

struct ResultRow {
  std::string run_id, scenario;
  std::uint64_t seed = 0;
  std::string algorithm, status;
  GridValues grid;
  std::map<std::string, double> metrics;  ///< column -> value as the file holds it; NaN for an empty cell
};

/// The value of a swept key in a row; nullptr when the row has no such key.
const std::string* GridValue(const ResultRow& row, const std::string& key);

/// The group a row belongs to in summary.md and --check: everything but the seed.
struct CellKey {
  std::string scenario;
  GridValues grid;
  std::string algorithm;
  auto operator<=>(const CellKey&) const = default;
  /// "scenario | key=value ... | algorithm", for messages.
  std::string Text() const;
};
CellKey CellOf(const ResultRow& row);

struct ResultsTable {
  std::vector<std::string> grid_keys;    ///< in column order
  std::vector<std::string> metric_keys;  ///< in column order
  std::vector<ResultRow> rows;
};

/// The fixed columns every results.csv starts with.
const std::vector<std::string>& ResultsFixedColumns();

/// A metric as results.csv writes it: 9 significant digits ("%.9g"); empty for NaN.
std::string ResultNumber(double value);
/// The value a reader of results.csv gets back for `value` (rounded to the file's digits),
/// so a summary built in memory equals one built from the file.
double AsWritten(double value);

std::string ResultsCsv(const ResultsTable& table);
/// Throws InputError (file, line, fix) for a missing or empty file, a header that does not
/// start with the fixed columns, a row with the wrong number of cells or a cell that is not
/// a number. Grid columns are those whose name has a dot (metric keys never have one).
ResultsTable ReadResultsCsv(const std::string& path);

}  // namespace slambox
