#pragma once
// Summary statistics of an error array, exactly as evo's PE.get_all_statistics defines
// them (numpy): rmse = sqrt(mean(e^2)), std with ddof 0, median averaging the two middle
// values of an even-sized array, sse = sum(e^2).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace slambox {

struct ErrorStatistics {
  int count = 0;
  double rmse = 0.0;
  double mean = 0.0;
  double median = 0.0;
  double std = 0.0;  ///< population standard deviation (ddof 0)
  double min = 0.0;
  double max = 0.0;
  double sse = 0.0;  ///< sum of squared errors
};

/// Statistics of `errors`; an empty array gives count 0 and NaN everywhere else.
ErrorStatistics ComputeStatistics(const std::vector<double>& errors);

/// numpy.percentile with linear interpolation (the default method); q in [0, 100].
/// NaN for an empty array.
double Percentile(std::vector<double> values, double q);

/// Student-t 0.975 quantile for `dof` degrees of freedom (the half-width factor of a
/// two-sided 95 % interval of a mean): table to 30, then 1.960 + 2.4/dof (within 0.002).
/// NaN for dof < 1.
double StudentT975(int dof);

/// Writes `<prefix>_rmse<unit>`, `_mean`, `_median`, `_std`, `_min`, `_max` and
/// `<prefix>_sse<sse_unit>` into `out`, null for an empty array. E.g. prefix "ate",
/// unit "_m", sse_unit "_m2" gives ate_rmse_m ... ate_sse_m2.
void AddStatistics(nlohmann::json& out, const std::string& prefix, const std::string& unit,
                   const std::string& sse_unit, const ErrorStatistics& stats);

/// A finite double as JSON, NaN/inf as null.
nlohmann::json NumberOrNull(double value);

}  // namespace slambox
