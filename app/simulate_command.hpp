#pragma once
// `slambox simulate NAME|FILE [--seed N] [--set k=v]... -o STREAM`: simulate a scenario
// once and write the stream file. Split out of the CLI11 wiring so tests can call it.
#include <cstdint>
#include <string>
#include <vector>

#include "sim/simulate.hpp"

namespace slambox {

struct SimulateRequest {
  std::string input;               ///< built-in scenario name or scenario YAML file
  std::uint64_t seed = 0;
  std::vector<std::string> sets;   ///< raw `--set key=value` arguments (scenario keys only)
  std::string output;              ///< stream file to write
};

struct SimulateSummary {
  Stream stream;
  SimulationReport report;
  std::string line;  ///< one-line summary: duration, distance, event counts
};

/// Throws InputError for `algo.*` keys, a stream file given as input, or a bad scenario.
SimulateSummary SimulateToFile(const SimulateRequest& request);

}  // namespace slambox
