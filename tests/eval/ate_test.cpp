#include "eval/ate.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace slambox {
namespace {

TEST(Ate, IdenticalTrajectoriesGiveExactlyZeroAlsoAtPi) {
  std::vector<SE2> gt = {SE2(0, 0, 0), SE2(1, 2, M_PI), SE2(-3, 1, -M_PI), SE2(4, 4, std::nextafter(M_PI, 0.0)),
                         SE2(5, 5, -M_PI + 1e-15)};
  const AbsoluteErrors e = AbsoluteTrajectoryErrors(gt, gt);
  for (size_t i = 0; i < gt.size(); ++i) {
    EXPECT_EQ(e.translation_m[i], 0.0);
    EXPECT_EQ(e.heading_rad[i], 0.0);
  }
}

TEST(Ate, HandComputed) {
  const std::vector<SE2> gt = {SE2(0, 0, 0), SE2(1, 1, 179.0 * M_PI / 180)};
  const std::vector<SE2> est = {SE2(3, 4, 0.1), SE2(1, 0, -179.0 * M_PI / 180)};
  const AbsoluteErrors e = AbsoluteTrajectoryErrors(gt, est);
  EXPECT_DOUBLE_EQ(e.translation_m[0], 5.0);
  EXPECT_DOUBLE_EQ(e.translation_m[1], 1.0);
  EXPECT_NEAR(e.heading_rad[0], 0.1, 1e-15);
  EXPECT_NEAR(e.heading_rad[1], 2.0 * M_PI / 180, 1e-12);  // across +-pi: 2 deg, not 358
  const auto deg = AbsDegrees(e.heading_rad);
  EXPECT_NEAR(deg[1], 2.0, 1e-10);
}

TEST(Ate, HeadingAtOppositeSidesOfPi) {
  // pi - eps vs -pi + eps differ by 2 eps, never ~2 pi (and never acos noise).
  const double eps = 1e-6;
  const AbsoluteErrors e = AbsoluteTrajectoryErrors({SE2(0, 0, M_PI - eps)}, {SE2(0, 0, -M_PI + eps)});
  EXPECT_NEAR(std::abs(e.heading_rad[0]), 2 * eps, 1e-12);
}

}  // namespace
}  // namespace slambox
