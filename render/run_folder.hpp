#pragma once
// Reads a run folder written by `slambox run` (layout fixed in DESIGN.md): metrics,
// ground truth, each module's trajectory, estimate and error series. Missing optional
// files leave their fields empty; figures that need them are skipped.
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/estimate.hpp"
#include "core/stream.hpp"
#include "core/world.hpp"

namespace slambox::render {

/// An error-over-distance/time series as eval wrote it (series/<algo>.json); null -> NaN.
struct ErrorSeries {
  std::vector<double> t_s, distance_m, ate_m, heading_error_deg, nees;
  double nees_band_lo = std::nan(""), nees_band_hi = std::nan("");
  std::vector<double> rpe_distance_m, rpe_trans_m, rpe_rot_deg;
};

struct AlgorithmResult {
  std::string name;
  std::string status;                    ///< "ok", "diverged", "failed"
  nlohmann::json metrics;                ///< its entry in metrics.json
  std::vector<StampedPose> trajectory;   ///< <algo>.tum (empty when missing)
  std::optional<Estimate> estimate;      ///< estimates/<algo>.json
  std::optional<ErrorSeries> series;     ///< series/<algo>.json
};

struct RunFolder {
  std::string dir;
  std::string scenario;
  long seed = 0;
  nlohmann::json metrics;
  World world;
  bool has_world = false;
  std::vector<StampedPose> groundtruth;
  std::vector<AlgorithmResult> algorithms;  ///< metrics.json order
};

/// Throws InputError when metrics.json is missing or any present file is malformed.
RunFolder ReadRunFolder(const std::string& dir);

/// Parses a JSON file; InputError with the file, the line and the parser's message.
nlohmann::json ReadJsonFile(const std::string& path);

/// Numbers of a JSON array (null or non-number -> NaN); empty for a missing key.
std::vector<double> NumbersOf(const nlohmann::json& j, const std::string& key);

}  // namespace slambox::render
