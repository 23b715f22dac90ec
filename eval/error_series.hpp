#pragma once
// The per-step error series of one module (series/<algo>.json): what the run figures plot.
// Written by the evaluator and read back by render through the same two functions.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace slambox {

struct LandmarkError {
  int id = -1;       ///< the module's landmark id
  int true_id = -1;  ///< the matched true landmark's id
  double error_m = NAN;
  double nees = NAN;  ///< NaN without a covariance
};

/// Null entries are NaN.
struct ErrorSeries {
  std::vector<double> t_s, distance_m;  ///< per matched pose; distance_m: ground-truth travel [m]
  std::vector<double> ate_m, heading_error_deg, nees;
  double nees_band_lo = NAN, nees_band_hi = NAN;  ///< two-sided 95 % band of per-step NEES (d = 3)
  std::vector<double> rpe_distance_m, rpe_trans_m, rpe_rot_deg;  ///< per RPE pair (distance at its end)
  std::vector<LandmarkError> landmarks;
};

nlohmann::json ToJson(const ErrorSeries& s);
/// Missing keys leave their fields empty; a malformed value throws InputError naming `path`.
ErrorSeries ErrorSeriesFromJson(const nlohmann::json& j, const std::string& path);

}  // namespace slambox
