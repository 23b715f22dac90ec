// The bounds of the module accuracy tests (tests/support/accuracy_bound.hpp): the ANEES
// window against closed forms (chi^2(2) exactly, Wilson-Hilferty for many dof), its coverage
// on simulated consistent runs, why it counts runs and not steps, and the headroom checks.
#include "tests/support/accuracy_bound.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace slambox {
namespace {

using testing::AneesNearMeasured;
using testing::NoWorseThanMeasured;
using testing::PoseAneesWindow;

/// z with Phi(z) = p: bisection on the normal CDF 0.5 erfc(-z / sqrt 2).
double NormalQuantile(double p) {
  double lo = -40.0, hi = 40.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

/// Wilson & Hilferty 1931: (X / k)^(1/3) is close to normal, mean 1 - 2/(9k), variance 2/(9k).
double ChiSquareQuantileWilsonHilferty(double p, double dof) {
  const double v = 2.0 / (9.0 * dof);
  return dof * std::pow(1.0 - v + NormalQuantile(p) * std::sqrt(v), 3);
}

TEST(AccuracyBound, AneesWindowMatchesClosedForms) {
  EXPECT_NEAR(NormalQuantile(0.995), 2.5758293035489, 1e-9);
  // chi^2(2) has the closed-form quantile -2 ln(1 - p): one run of a 2-d error.
  const NeesBand two = AneesBand(2, 1, 0.99);
  EXPECT_NEAR(two.lo, -2 * std::log(1 - 0.005), 1e-9);
  EXPECT_NEAR(two.hi, -2 * std::log(0.005), 1e-9);
  // Wilson-Hilferty's relative error at the 0.5 % / 99.5 % quantiles is 0.3 % / 0.08 % at 30
  // dof and 6e-5 / 4e-5 at 300 (16 % in the lower tail at 3 dof: no oracle there).
  for (int runs : {10, 100, 1000}) {
    const NeesBand w = PoseAneesWindow(runs);
    const double tol = 0.1 / (3 * runs);
    EXPECT_NEAR(w.lo / (ChiSquareQuantileWilsonHilferty(0.005, 3 * runs) / runs), 1.0, tol) << runs;
    EXPECT_NEAR(w.hi / (ChiSquareQuantileWilsonHilferty(0.995, 3 * runs) / runs), 1.0, tol) << runs;
  }
}

/// Mean NEES of one simulated run: `steps` 3-d errors e_k = phi e_{k-1} + sqrt(1 - phi^2) w_k,
/// each distributed as N(0, I) (a consistent covariance), correlated in time by phi.
double RunAnees(std::mt19937_64& rng, int steps, double phi) {
  std::normal_distribution<double> n01;
  double e[3] = {n01(rng), n01(rng), n01(rng)}, sum = 0.0;
  for (int k = 0; k < steps; ++k) {
    for (double& x : e) x = phi * x + std::sqrt(1 - phi * phi) * n01(rng);
    sum += e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
  }
  return sum / steps;
}

TEST(AccuracyBound, AneesWindowCoverageCountsRunsNotSteps) {
  // 10 consistent runs of 1000 steps: independent steps (phi = 0) never land outside the
  // per-run window (it is wide for them); errors correlated over the whole run (phi = 0.998,
  // about 500 steps) land outside the per-step window most of the time but rarely outside
  // the per-run one; a covariance 2x too small (NEES doubled) leaves the per-run window often.
  std::mt19937_64 rng(7);
  const int trials = 200, runs = 10, steps = 1000;
  const NeesBand per_run = PoseAneesWindow(runs), per_step = PoseAneesWindow(runs * steps);
  int iid_out = 0, corr_out_steps = 0, corr_out_runs = 0, doubled_out = 0;
  for (int t = 0; t < trials; ++t) {
    double iid = 0.0, corr = 0.0;
    for (int r = 0; r < runs; ++r) iid += RunAnees(rng, steps, 0.0) / runs, corr += RunAnees(rng, steps, 0.998) / runs;
    iid_out += (iid < per_run.lo || iid > per_run.hi) ? 1 : 0;
    corr_out_steps += (corr < per_step.lo || corr > per_step.hi) ? 1 : 0;
    corr_out_runs += (corr < per_run.lo || corr > per_run.hi) ? 1 : 0;
    doubled_out += (2 * corr > per_run.hi) ? 1 : 0;
  }
  EXPECT_EQ(iid_out, 0);
  EXPECT_GT(corr_out_steps, trials / 2);
  EXPECT_LT(corr_out_runs, trials / 50);
  EXPECT_GT(doubled_out, trials / 4);
}

TEST(AccuracyBound, HeadroomChecks) {
  EXPECT_TRUE(NoWorseThanMeasured(0.15, 0.1));
  EXPECT_FALSE(NoWorseThanMeasured(0.151, 0.1));
  EXPECT_FALSE(NoWorseThanMeasured(NAN, 0.1));
  const NeesBand w = PoseAneesWindow(10);  // [1.38, 5.37]
  EXPECT_NEAR(w.lo, 1.3787, 1e-3);
  EXPECT_NEAR(w.hi, 5.3672, 1e-3);
  EXPECT_TRUE(AneesNearMeasured(3.0, 2.5, w));
  EXPECT_FALSE(AneesNearMeasured(1.6, 2.5, w));   // in the window, below measured / 1.5
  EXPECT_FALSE(AneesNearMeasured(3.9, 2.5, w));   // in the window, above 1.5 x measured
  EXPECT_FALSE(AneesNearMeasured(5.5, 4.0, w));   // near measured, out of the window
  EXPECT_FALSE(AneesNearMeasured(NAN, 3.0, w));
}

}  // namespace
}  // namespace slambox
