#include "sim/bounded_atan2.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace slambox {
namespace {

/// The shorter angle between a and b.
double AngleGap(double a, double b) {
  const double d = std::remainder(a - b, 2.0 * M_PI);
  return std::abs(d);
}

TEST(BoundedAtan2, WithinItsStatedErrorOfStdAtan2EverywhereAroundTheCircle) {
  double worst = 0.0;
  for (const double radius : {1e-300, 1e-9, 1.0, 37.5, 1e12}) {
    for (int i = 0; i <= 2'000'000; ++i) {
      const double t = -M_PI + 2.0 * M_PI * i / 2'000'000;
      const double y = radius * std::sin(t), x = radius * std::cos(t);
      worst = std::max(worst, AngleGap(BoundedAtan2(y, x), std::atan2(y, x)));
    }
  }
  EXPECT_LE(worst, kBoundedAtan2ErrorRad);
  // The bound is tight enough to matter: a tenth of it would be wrong (the polynomial's error).
  EXPECT_GT(worst, 0.1 * kBoundedAtan2ErrorRad);
}

TEST(BoundedAtan2, AxesOctantBoundariesAndTheOrigin) {
  EXPECT_EQ(BoundedAtan2(0.0, 0.0), 0.0);
  EXPECT_NEAR(BoundedAtan2(0.0, 2.0), 0.0, 1e-12);
  EXPECT_NEAR(BoundedAtan2(2.0, 0.0), M_PI_2, 1e-12);
  EXPECT_NEAR(BoundedAtan2(-2.0, 0.0), -M_PI_2, 1e-12);
  EXPECT_NEAR(std::abs(BoundedAtan2(0.0, -2.0)), M_PI, 1e-12);  // +-pi: the same direction
  for (const double sx : {-1.0, 1.0})
    for (const double sy : {-1.0, 1.0})
      EXPECT_NEAR(BoundedAtan2(sy * 3.0, sx * 3.0), std::atan2(sy, sx), kBoundedAtan2ErrorRad);
  // Either side of +-pi (the wrap): the sign follows y.
  EXPECT_GT(BoundedAtan2(1e-9, -1.0), 3.14);
  EXPECT_LT(BoundedAtan2(-1e-9, -1.0), -3.14);
}

}  // namespace
}  // namespace slambox
