#pragma once
// atan2 to within a stated error, where the angle only picks something: the ICP's
// projection search picks a beam by a point's bearing (slam/icp.cpp), the simulator's
// CastFan picks the beams a wall subtends (sim/ray_fan.cpp; std::atan2 was 9 % of
// `slambox simulate loop`). Callers widen what they pick by kFastAtan2ErrorRad, so the
// results they compute exactly do not change.
#include <algorithm>
#include <cmath>

namespace slambox {

/// |FastAtan2(y, x) - atan2(y, x)| <= kFastAtan2ErrorRad (as angles: -pi and pi are the same
/// direction) for all finite (y, x); tests/core/fast_atan2_test.cpp measures 1.15e-5 rad over a
/// dense sweep of directions and radii.
inline constexpr double kFastAtan2ErrorRad = 2e-5;

/// atan2(y, x) in [-pi, pi]: the octant by symmetry, then atan(a), a in [0, 1], by the odd
/// polynomial of Abramowitz & Stegun 4.4.49; (0, 0) gives 0. Its error is the same, to
/// rounding, in opposite directions (FastAtan2(-y, -x) = FastAtan2(y, x) -+ pi). Branch-free
/// so that loops over it vectorize.
inline double FastAtan2(double y, double x) {
  const double ax = std::abs(x), ay = std::abs(y);
  const double mx = std::max(ax, ay), mn = std::min(ax, ay);
  const double a = mx > 0.0 ? mn / mx : 0.0, a2 = a * a;
  double r = a * (0.9998660 + a2 * (-0.3302995 + a2 * (0.1801410 + a2 * (-0.0851330 + a2 * 0.0208351))));
  r = ay > ax ? M_PI_2 - r : r;
  r = x < 0 ? M_PI - r : r;
  return y < 0 ? -r : r;
}

}  // namespace slambox
