#pragma once
// Chi-square distribution: CDF through the regularized lower incomplete gamma function
// P(k/2, x/2) and quantiles by bisection on the CDF. Used for NEES consistency bands
// (Bar-Shalom, Li, Kirubarajan 2001, Sec. 5.4.2).
namespace slambox {

/// Regularized lower incomplete gamma P(a, x) = gamma(a, x) / Gamma(a), a > 0, x >= 0:
/// power series for x < a + 1, Lentz's continued fraction for Q = 1 - P otherwise
/// (Abramowitz & Stegun 6.5.29 and 6.5.31).
double RegularizedLowerGamma(double a, double x);

/// P(X <= x) for X ~ chi^2 with `dof` degrees of freedom.
double ChiSquareCdf(double x, double dof);

/// The x with ChiSquareCdf(x, dof) = p, for p in (0, 1); relative accuracy ~1e-12.
double ChiSquareQuantile(double p, double dof);

/// Two-sided band for the average NEES of `dims`-dimensional errors over `runs`
/// independent runs: runs * ANEES ~ chi^2(runs * dims), so the band is
/// [q((1-c)/2), q((1+c)/2)] / runs. E.g. dims 3, runs 50, c 0.95: [2.36, 3.72].
struct NeesBand {
  double lo = 0.0;
  double hi = 0.0;
};
NeesBand AneesBand(int dims, int runs, double confidence = 0.95);

}  // namespace slambox
