#pragma once
// A sweep file (DESIGN.md, "Output of slambox sweep") and its expansion into runs.
//   scenarios: [loop, tunnel]          # built-in names or scenario files
//   algorithms: [icp-poseslam, odometry] # or [all]
//   seeds: 10                          # seeds 0..9, or a list [0, 4, 7]
//   grid:                              # cartesian product of overrides
//     sensors.lidar.sigma_range_m: [0.01, 0.05]
//   set: {robot.laps: 1}               # optional: fixed overrides for every run
//   timeout_s: 600                     # optional: a run taking longer is killed, recorded failed
//   plugins: [build/libmy_plugin.so]   # optional: module plugins (paths relative to this file)
//   relations: {intel.stream: intel.relations}  # optional: Kümmerle relations per scenario entry
//   interval: auto                     # optional: summary.md's 95 % interval of a mean: auto
//                                      # (Student-t from 10 seeds, percentile bootstrap below), t, bootstrap
// A run = one scenario x one grid point x one seed; it simulates its stream once and
// replays it to every algorithm. A `scenarios` entry may be a stream file (e.g. a
// converted log): it is already simulated, so it is run once per grid point (seed 0 in
// results) and only algo.NAME.FIELD keys may be set or swept.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "eval/statistics.hpp"

namespace slambox {

struct SweepSpec {
  std::string source;  ///< the sweep file, for messages
  std::vector<std::string> scenarios;
  std::vector<std::string> algorithms;
  std::vector<std::uint64_t> seeds;
  std::vector<std::pair<std::string, std::vector<std::string>>> grid;  ///< key -> values (YAML text), file order
  std::vector<std::pair<std::string, std::string>> fixed;              ///< `set:` key -> value
  double timeout_s = 1800.0;
  std::vector<std::string> plugins;  ///< module plugin files, resolved against the sweep file's folder
  std::vector<std::pair<std::string, std::string>> relations;  ///< scenario entry -> relations file
  /// `check:` metric -> (relative, absolute) tolerance for `sweep --check` (else the flags').
  std::vector<std::pair<std::string, std::pair<double, double>>> check_tolerances;
  IntervalMethod interval = IntervalMethod::kAuto;  ///< `interval:` (summary.md, report, figures)
};

struct SweepRun {
  std::size_t index = 0;  ///< position in the expansion (shards are index % N)
  std::string id;         ///< 16 hex digits: hash of scenario, overrides, seed, slambox version
  std::string scenario;
  std::uint64_t seed = 0;
  std::vector<std::pair<std::string, std::string>> grid_values;  ///< this run's value of each grid key
  std::vector<std::string> sets;  ///< every "key=value" override (fixed then grid)
  bool is_stream = false;         ///< `scenario` is a stream file: no seed, no scenario overrides
  std::string relations;          ///< relations file for this run, or empty
};

/// Parses and validates; throws InputError with file, line and fix.
SweepSpec LoadSweepSpec(const std::string& path);
/// LoadSweepSpec of the file's text; `path` is used in error messages.
SweepSpec ParseSweepSpec(const std::string& text, const std::string& path);
/// Scenario-major, then grid points (last key varies fastest), then seeds.
std::vector<SweepRun> ExpandSweep(const SweepSpec& spec);
/// Stable run id (FNV-1a 64 of the canonical run description and slambox version).
/// A non-empty `relations` file is part of the description (it changes the metrics).
std::string RunId(const std::string& scenario, const std::vector<std::string>& sets, std::uint64_t seed,
                  const std::string& relations = "");

}  // namespace slambox
