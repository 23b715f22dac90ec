#include "eval/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace slambox {

ErrorStatistics ComputeStatistics(const std::vector<double>& errors) {
  ErrorStatistics s;
  s.count = static_cast<int>(errors.size());
  if (errors.empty()) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    s.rmse = s.mean = s.median = s.std = s.min = s.max = s.sse = nan;
    return s;
  }
  const double n = static_cast<double>(errors.size());
  double sum = 0.0, sse = 0.0;
  for (double e : errors) {
    sum += e;
    sse += e * e;
  }
  s.mean = sum / n;
  s.sse = sse;
  s.rmse = std::sqrt(sse / n);
  double var = 0.0;  // two-pass: numerically stable, as numpy.std
  for (double e : errors) var += (e - s.mean) * (e - s.mean);
  s.std = std::sqrt(var / n);
  s.min = *std::min_element(errors.begin(), errors.end());
  s.max = *std::max_element(errors.begin(), errors.end());
  s.median = Percentile(errors, 50.0);
  return s;
}

double Percentile(std::vector<double> values, double q) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  // numpy "linear": position (n - 1) q / 100 between the two neighbouring order statistics.
  const double pos = (static_cast<double>(values.size()) - 1.0) * q / 100.0;
  const auto lo = static_cast<size_t>(std::floor(pos));
  const size_t hi = std::min(lo + 1, values.size() - 1);
  const double frac = pos - static_cast<double>(lo);
  if (frac == 0.0) return values[lo];
  if (values[lo] == values[hi]) return values[lo];
  // For the median of an even array (frac = 0.5) this is (a + b) / 2, as numpy.median.
  if (frac == 0.5) return (values[lo] + values[hi]) / 2.0;
  // numpy's _lerp: interpolate from the nearer end.
  const double diff = values[hi] - values[lo];
  return frac >= 0.5 ? values[hi] - diff * (1.0 - frac) : values[lo] + diff * frac;
}

nlohmann::json NumberOrNull(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

SampleSummary Summarize(std::vector<double> v) {
  std::erase_if(v, [](double x) { return std::isnan(x); });
  SampleSummary s;
  s.n = static_cast<int>(v.size());
  if (v.empty()) return s;
  double sum = 0.0;
  for (double x : v) sum += x;
  s.mean = sum / s.n;
  double ss = 0.0;
  for (double x : v) ss += (x - s.mean) * (x - s.mean);
  s.std = s.n > 1 ? std::sqrt(ss / (s.n - 1)) : 0.0;
  s.ci95_half = s.n > 1 ? StudentT975(s.n - 1) * s.std / std::sqrt(s.n) : 0.0;
  std::sort(v.begin(), v.end());
  s.median = Percentile(v, 50.0);
  s.q1 = Percentile(v, 25.0);
  s.q3 = Percentile(v, 75.0);
  const double iqr = s.q3 - s.q1, lo_fence = s.q1 - 1.5 * iqr, hi_fence = s.q3 + 1.5 * iqr;
  s.whisker_lo = s.q1;
  s.whisker_hi = s.q3;
  for (double x : v) {
    if (x < lo_fence || x > hi_fence) {
      s.outliers.push_back(x);
    } else {
      s.whisker_lo = std::min(s.whisker_lo, x);
      s.whisker_hi = std::max(s.whisker_hi, x);
    }
  }
  return s;
}

double StudentT975(int dof) {
  static const double kTable[] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228,
                                  2.201,  2.179, 2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086,
                                  2.080,  2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042};
  if (dof < 1) return std::nan("");
  return dof <= 30 ? kTable[dof - 1] : 1.960 + 2.4 / dof;
}

}  // namespace slambox
