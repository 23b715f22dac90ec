#pragma once
// atan2 to within a stated error, for culling only: CastFan needs the angle a wall's end
// points subtend to pick the beams worth testing, not the angle itself, so an estimate
// whose error is known can stand in for std::atan2 (9 % of `slambox simulate loop`,
// callgrind) if every interval it gives is widened by that error. The hit tests themselves
// stay exact, so the ranges do not change by a bit.
#include <algorithm>
#include <cmath>

namespace slambox {

/// |BoundedAtan2(y, x) - std::atan2(y, x)| <= kBoundedAtan2ErrorRad for all finite (y, x)
/// (tests/sim/bounded_atan2_test.cpp: the maximum over a dense sweep of directions is 1.15e-5).
inline constexpr double kBoundedAtan2ErrorRad = 2e-5;

/// atan2(y, x) in [-pi, pi]: the octant by symmetry, then atan(a), a in [0, 1], by the
/// odd polynomial of Abramowitz & Stegun 4.4.49; (0, 0) gives 0, and -pi and pi are
/// not told apart (an angle, not a branch of atan2: callers reduce it modulo 2 pi).
inline double BoundedAtan2(double y, double x) {
  const double ax = std::abs(x), ay = std::abs(y);
  const double hi = std::max(ax, ay);
  if (hi == 0.0) return 0.0;
  const double a = std::min(ax, ay) / hi, s = a * a;
  double r = a * (0.9998660 + s * (-0.3302995 + s * (0.1801410 + s * (-0.0851330 + s * 0.0208351))));
  if (ay > ax) r = M_PI_2 - r;
  if (x < 0.0) r = M_PI - r;
  return y < 0.0 ? -r : r;
}

}  // namespace slambox
