#include "core/chi_square.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace slambox {
namespace {

TEST(ChiSquare, CdfMatchesClosedForms) {
  for (double x : {1e-4, 0.01, 0.3, 1.0, 2.5, 7.0, 15.0, 40.0}) {
    EXPECT_NEAR(ChiSquareCdf(x, 1.0), std::erf(std::sqrt(x / 2.0)), 1e-12) << x;   // chi^2_1
    EXPECT_NEAR(ChiSquareCdf(x, 2.0), 1.0 - std::exp(-x / 2.0), 1e-12) << x;       // exponential
    EXPECT_NEAR(ChiSquareCdf(x, 4.0), 1.0 - std::exp(-x / 2.0) * (1.0 + x / 2.0), 1e-12) << x;
  }
  EXPECT_EQ(ChiSquareCdf(0.0, 3.0), 0.0);
}

TEST(ChiSquare, QuantileInvertsCdf) {
  for (double dof : {1.0, 2.0, 3.0, 7.0, 150.0})
    for (double p : {0.001, 0.025, 0.5, 0.95, 0.975, 0.999})
      EXPECT_NEAR(ChiSquareCdf(ChiSquareQuantile(p, dof), dof), p, 1e-10) << dof << " " << p;
  EXPECT_NEAR(ChiSquareQuantile(0.95, 2.0), -2.0 * std::log(0.05), 1e-9);
}

TEST(ChiSquare, QuantilesMatchTables) {
  // Standard tables (e.g. NIST/SEMATECH e-Handbook 1.3.6.7.4), 3+ significant decimals.
  EXPECT_NEAR(ChiSquareQuantile(0.95, 3), 7.815, 1e-3);
  EXPECT_NEAR(ChiSquareQuantile(0.95, 2), 5.991, 1e-3);
  EXPECT_NEAR(ChiSquareQuantile(0.975, 1), 5.024, 1e-3);
  EXPECT_NEAR(ChiSquareQuantile(0.025, 3), 0.216, 1e-3);
  EXPECT_NEAR(ChiSquareQuantile(0.99, 10), 23.209, 1e-3);
  EXPECT_NEAR(ChiSquareQuantile(0.05, 10), 3.940, 1e-3);
  EXPECT_NEAR(ChiSquareQuantile(0.975, 100), 129.561, 1e-3);
  EXPECT_NEAR(ChiSquareQuantile(0.025, 100), 74.222, 1e-3);
}

TEST(ChiSquare, AneesBandForThreeDimsFiftyRuns) {
  const NeesBand b = AneesBand(3, 50, 0.95);  // Bar-Shalom et al.: [2.36, 3.72]
  EXPECT_NEAR(b.lo, 2.36, 0.005);
  EXPECT_NEAR(b.hi, 3.72, 0.005);
  const NeesBand one = AneesBand(3, 1, 0.95);
  EXPECT_NEAR(one.lo, 0.216, 1e-3);
  EXPECT_NEAR(one.hi, 9.348, 1e-3);
}

}  // namespace
}  // namespace slambox
