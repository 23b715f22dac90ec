#include "core/fast_atan2.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace slambox {
namespace {

/// The shorter angle between a and b.
double AngleGap(double a, double b) { return std::abs(std::remainder(a - b, 2.0 * M_PI)); }

TEST(FastAtan2, WithinItsStatedErrorOfStdAtan2EverywhereAroundTheCircle) {
  double worst = 0.0;
  for (const double radius : {1e-300, 1e-9, 0.1, 1.0, 37.5, 1e12}) {
    for (int i = 0; i <= 2'000'000; ++i) {
      const double t = -M_PI + 2.0 * M_PI * i / 2'000'000;
      const double y = radius * std::sin(t), x = radius * std::cos(t);
      worst = std::max(worst, AngleGap(FastAtan2(y, x), std::atan2(y, x)));
    }
  }
  EXPECT_LE(worst, kFastAtan2ErrorRad);
  // The bound is close to the polynomial's error, not a loose guess.
  EXPECT_GT(worst, 0.5 * kFastAtan2ErrorRad);
}

TEST(FastAtan2, OppositeDirectionsHaveTheSameErrorToRounding) {
  // CastFan relies on it to pick the short way round a wall it nearly touches.
  for (int i = 0; i < 100'000; ++i) {
    const double t = -M_PI + 2.0 * M_PI * (i + 0.5) / 100'000;
    const double y = std::sin(t), x = std::cos(t);
    EXPECT_NEAR(AngleGap(FastAtan2(y, x), FastAtan2(-y, -x)), M_PI, 1e-15);
  }
}

TEST(FastAtan2, AxesQuadrantsTheWrapAndTheOrigin) {
  EXPECT_EQ(FastAtan2(0.0, 0.0), 0.0);
  EXPECT_NEAR(FastAtan2(0.0, 2.0), 0.0, 1e-12);
  EXPECT_NEAR(FastAtan2(2.0, 0.0), M_PI_2, 1e-12);
  EXPECT_NEAR(FastAtan2(-2.0, 0.0), -M_PI_2, 1e-12);
  EXPECT_NEAR(std::abs(FastAtan2(0.0, -2.0)), M_PI, 1e-12);
  for (const double sx : {-1.0, 1.0})
    for (const double sy : {-1.0, 1.0}) EXPECT_NEAR(FastAtan2(sy * 3.0, sx * 3.0), std::atan2(sy, sx), kFastAtan2ErrorRad);
  // Either side of +-pi: the sign follows y.
  EXPECT_GT(FastAtan2(1e-9, -1.0), 3.14);
  EXPECT_LT(FastAtan2(-1e-9, -1.0), -3.14);
}

}  // namespace
}  // namespace slambox
