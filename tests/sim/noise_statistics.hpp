#pragma once
// Confidence-bound checks of sampled noise against a configured standard deviation.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/chi_square.hpp"

namespace slambox::testing {

/// Mean within 4 sigma / sqrt(n) of `mean`, and (n-1) s^2 / sigma^2 inside the two-sided
/// 99.9% chi-square interval.
inline void ExpectGaussian(const std::vector<double>& samples, double mean, double sigma, const char* what) {
  const double n = static_cast<double>(samples.size());
  double sum = 0.0;
  for (double v : samples) sum += v;
  const double m = sum / n;
  double ss = 0.0;
  for (double v : samples) ss += (v - m) * (v - m);
  EXPECT_NEAR(m, mean, 4.0 * sigma / std::sqrt(n)) << what;
  const double statistic = ss / (sigma * sigma);
  EXPECT_GT(statistic, ChiSquareQuantile(0.0005, n - 1)) << what << ": sample std " << std::sqrt(ss / (n - 1));
  EXPECT_LT(statistic, ChiSquareQuantile(0.9995, n - 1)) << what << ": sample std " << std::sqrt(ss / (n - 1));
}

/// A count from n Bernoulli(p) trials within 4 standard deviations.
inline void ExpectBinomial(double count, double n, double p, const char* what) {
  EXPECT_NEAR(count, n * p, 4.0 * std::sqrt(n * p * (1.0 - p)) + 1.0) << what;
}

}  // namespace slambox::testing
