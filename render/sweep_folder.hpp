#pragma once
// Reads a sweep folder written by `slambox sweep`: sweep.json (the order of scenarios and
// algorithms) and results.csv through eval's one reader (eval/results_table.hpp).
#include <string>
#include <vector>

#include "eval/results_table.hpp"
#include "eval/statistics.hpp"

namespace slambox::render {

struct SweepFolder {
  std::string dir;
  std::vector<std::string> scenarios, algorithms;  ///< only those with rows, sweep.json's order first
  std::vector<bool> baseline;  ///< per algorithm: sweep.json's modules.<algo>.baseline
  IntervalMethod interval = IntervalMethod::kAuto;  ///< sweep.json's `interval`
  ResultsTable results;
};

/// Throws InputError (file, line, fix) for a missing or malformed sweep.json / results.csv.
SweepFolder ReadSweepFolder(const std::string& dir);

}  // namespace slambox::render
