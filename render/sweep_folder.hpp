#pragma once
// Reads a sweep folder written by `slambox sweep`: sweep.json and results.csv (one row per
// run and algorithm; an empty cell is null).
#include <map>
#include <string>
#include <vector>

namespace slambox::render {

struct SweepRow {
  std::string scenario, algorithm, status;
  long seed = 0;
  std::map<std::string, std::string> grid;     ///< swept key -> value as written
  std::map<std::string, double> metrics;       ///< metric -> value (NaN for null)
};

struct SweepFolder {
  std::string dir;
  std::vector<std::string> scenarios, algorithms, grid_keys, metric_keys;
  std::vector<SweepRow> rows;
};

/// Throws InputError (file, line, fix) for a missing sweep.json / results.csv, a header
/// without the fixed columns, or a row with the wrong number of cells.
SweepFolder ReadSweepFolder(const std::string& dir);

/// Display statistics of one group of values (NaNs ignored): quartiles by linear
/// interpolation (Hyndman & Fan type 7), Tukey whiskers (most extreme values within
/// 1.5 IQR of the box), mean and a 95% Student-t interval of the mean.
struct GroupStats {
  int n = 0;
  double q1 = 0, median = 0, q3 = 0, whisker_lo = 0, whisker_hi = 0;
  double mean = 0, ci95_half = 0;  ///< t_{0.975, n-1} s / sqrt(n); 0 for n < 2
  std::vector<double> outliers;
};
GroupStats Describe(std::vector<double> values);

}  // namespace slambox::render
