#include "core/chi_square.hpp"

#include <cassert>
#include <cmath>
#include <limits>

namespace slambox {

namespace {
// Series: P(a, x) = e^-x x^a / Gamma(a+1) * sum_n x^n / ((a+1)...(a+n)).
double LowerGammaSeries(double a, double x) {
  double term = 1.0 / a, sum = term;
  for (int n = 1; n < 1000; ++n) {
    term *= x / (a + n);
    sum += term;
    if (std::abs(term) < std::abs(sum) * 1e-16) break;
  }
  return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// Continued fraction for Q(a, x) = e^-x x^a / Gamma(a) * 1/(x+1-a- 1(1-a)/(x+3-a- ...)),
// evaluated with the modified Lentz method.
double UpperGammaFraction(double a, double x) {
  const double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 1000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-16) break;
  }
  return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}
}  // namespace

double RegularizedLowerGamma(double a, double x) {
  assert(a > 0.0);
  if (x <= 0.0) return 0.0;
  if (x < a + 1.0) return LowerGammaSeries(a, x);
  return 1.0 - UpperGammaFraction(a, x);
}

double ChiSquareCdf(double x, double dof) { return RegularizedLowerGamma(dof / 2.0, x / 2.0); }

double ChiSquareQuantile(double p, double dof) {
  assert(p > 0.0 && p < 1.0 && dof > 0.0);
  double lo = 0.0, hi = std::max(1.0, dof);
  while (ChiSquareCdf(hi, dof) < p) {
    lo = hi;
    hi *= 2.0;
  }
  // The CDF is monotone: bisection converges unconditionally.
  for (int i = 0; i < 200 && hi - lo > 1e-13 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (ChiSquareCdf(mid, dof) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

NeesBand AneesBand(int dims, int runs, double confidence) {
  assert(dims > 0 && runs > 0 && confidence > 0.0 && confidence < 1.0);
  const double dof = static_cast<double>(dims) * runs;
  return {ChiSquareQuantile((1.0 - confidence) / 2.0, dof) / runs,
          ChiSquareQuantile((1.0 + confidence) / 2.0, dof) / runs};
}

}  // namespace slambox
