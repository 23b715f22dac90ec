#include "eval/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <tuple>
#include <utility>

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

const char* IntervalMethodName(IntervalMethod method) {
  switch (method) {
    case IntervalMethod::kAuto: return "auto";
    case IntervalMethod::kStudentT: return "t";
    case IntervalMethod::kBootstrap: return "bootstrap";
  }
  return "?";
}

std::optional<IntervalMethod> IntervalMethodFromName(const std::string& word) {
  for (IntervalMethod m : {IntervalMethod::kAuto, IntervalMethod::kStudentT, IntervalMethod::kBootstrap})
    if (word == IntervalMethodName(m)) return m;
  return std::nullopt;
}

IntervalMethod ResolveInterval(IntervalMethod method, int n) {
  if (method != IntervalMethod::kAuto) return method;
  return n >= 10 ? IntervalMethod::kStudentT : IntervalMethod::kBootstrap;
}

namespace {

// Every multiset of n draws from v (counts c_i summing to n) with probability
// n! / (prod c_i!) / n^n: the exact bootstrap distribution of the mean.
void EnumerateResamples(const std::vector<double>& v, size_t i, int left, double sum, double log_weight,
                        std::vector<std::pair<double, double>>& out) {
  const int n = static_cast<int>(v.size());
  if (i + 1 == v.size()) {
    const double w = log_weight - std::lgamma(left + 1.0);
    out.push_back({(sum + left * v[i]) / n, w});
    return;
  }
  for (int c = 0; c <= left; ++c)
    EnumerateResamples(v, i + 1, left - c, sum + c * v[i], log_weight - std::lgamma(c + 1.0), out);
}

std::pair<double, double> BootstrapPercentiles(const std::vector<double>& v) {
  const int n = static_cast<int>(v.size());
  if (n <= 9) {
    std::vector<std::pair<double, double>> means;  // (mean, log weight without n! / n^n)
    EnumerateResamples(v, 0, n, 0.0, 0.0, means);
    std::sort(means.begin(), means.end());
    const double log_scale = std::lgamma(n + 1.0) - n * std::log(static_cast<double>(n));
    // The smallest mean whose cumulative probability reaches 2.5 % (97.5 %): the inverse CDF.
    double cum = 0.0, lo = NAN, hi = NAN;
    for (const auto& [m, lw] : means) {
      cum += std::exp(lw + log_scale);
      if (std::isnan(lo) && cum >= 0.025 - 1e-12) lo = m;
      if (std::isnan(hi) && cum >= 0.975 - 1e-12) hi = m;
    }
    return {lo, std::isnan(hi) ? means.back().first : hi};
  }
  constexpr int kResamples = 20000;
  std::mt19937_64 rng(0x5eed);  // fixed: the same values give the same interval
  std::vector<double> means(kResamples);
  for (double& m : means) {
    double sum = 0.0;
    for (int k = 0; k < n; ++k) sum += v[rng() % static_cast<std::uint64_t>(n)];
    m = sum / n;
  }
  return {Percentile(means, 2.5), Percentile(means, 97.5)};
}

}  // namespace

MeanInterval IntervalOfMean(std::vector<double> v, IntervalMethod method, bool nonnegative) {
  std::erase_if(v, [](double x) { return std::isnan(x); });
  std::sort(v.begin(), v.end());  // the result does not depend on the order of the runs
  MeanInterval out;
  out.n = static_cast<int>(v.size());
  out.method = ResolveInterval(method, out.n);
  if (v.empty()) return out;
  if (out.method == IntervalMethod::kBootstrap) {
    std::tie(out.lo, out.hi) = BootstrapPercentiles(v);
    return out;
  }
  const SampleSummary s = Summarize(v);
  out.lo = s.mean - s.ci95_half;
  out.hi = s.mean + s.ci95_half;
  if (nonnegative && out.lo < 0.0) {
    out.lo = 0.0;
    out.clipped = true;
  }
  return out;
}

double StudentT975(int dof) {
  static const double kTable[] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228,
                                  2.201,  2.179, 2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086,
                                  2.080,  2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042};
  if (dof < 1) return std::nan("");
  return dof <= 30 ? kTable[dof - 1] : 1.960 + 2.4 / dof;
}

}  // namespace slambox
