#pragma once
// Summary statistics of an error array, exactly as evo's PE.get_all_statistics defines
// them (numpy): rmse = sqrt(mean(e^2)), std with ddof 0, median averaging the two middle
// values of an even-sized array, sse = sum(e^2).
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
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

/// Statistics of one group of values over runs (a sweep cell, a box of a figure), NaNs
/// ignored: sample std (n - 1; 0 for n = 1), the numpy median, quartiles by linear
/// interpolation (Hyndman & Fan type 7, numpy's default), Tukey whiskers (the most extreme
/// values within 1.5 IQR of the box) and the half-width of the 95 % Student-t interval of
/// the mean, t(0.975, n - 1) std / sqrt(n) (0 for n < 2).
struct SampleSummary {
  int n = 0;
  double mean = 0, std = 0, median = 0, ci95_half = 0;
  double q1 = 0, q3 = 0, whisker_lo = 0, whisker_hi = 0;
  std::vector<double> outliers;
};
SampleSummary Summarize(std::vector<double> values);

/// How a sweep's 95 % interval of a cell's mean is computed (`interval:` in a sweep file).
/// kAuto: Student-t from 10 values on (where the mean is close enough to normal), the
/// percentile bootstrap below. The t-interval of 3 seeds is 4.3 std / sqrt(3) wide on
/// either side and goes below zero for a skewed error; the bootstrap's ends are means of
/// resamples, so they stay within the values (never below zero for errors).
enum class IntervalMethod { kAuto, kStudentT, kBootstrap };
/// "auto", "t", "bootstrap" (the sweep file's words).
const char* IntervalMethodName(IntervalMethod method);
/// The method of a sweep file's word; nullopt for another word.
std::optional<IntervalMethod> IntervalMethodFromName(const std::string& word);
/// The method `method` means for `n` values (kAuto resolved; never kAuto).
IntervalMethod ResolveInterval(IntervalMethod method, int n);

struct MeanInterval {
  int n = 0;
  double lo = NAN, hi = NAN;  ///< NaN for n = 0; lo = hi = the value for n = 1
  IntervalMethod method = IntervalMethod::kStudentT;  ///< as resolved
  bool clipped = false;  ///< the t-interval's lower end was raised to 0 (a non-negative metric)
};
/// 95 % interval of the mean of `values` (NaNs ignored). Bootstrap: the 2.5 % and 97.5 %
/// points of the distribution of resample means (Efron & Tibshirani 1993, ch. 13), exact
/// (every multiset of n draws with its multinomial weight) for n <= 9, else 20000 resamples
/// of a fixed-seed generator, so the same values give the same interval. With
/// `nonnegative`, a t-interval's lower end is clipped at 0.
MeanInterval IntervalOfMean(std::vector<double> values, IntervalMethod method, bool nonnegative);

/// A finite double as JSON, NaN/inf as null.
nlohmann::json NumberOrNull(double value);

}  // namespace slambox
