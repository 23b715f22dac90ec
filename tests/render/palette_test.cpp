// Module colours: odometry is always orange, and the registry's modules (plus room to
// grow) get distinct colours, the same for a module wherever it sits after odometry.
#include "render/palette.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <tuple>

namespace slambox::render {
namespace {

TEST(Palette, FifteenModulesBesidesOdometryGetDistinctColours) {
  std::vector<std::string> names = {"odometry"};
  for (int i = 0; i < 15; ++i) names.push_back("m" + std::to_string(i));
  std::set<std::tuple<int, int, int>> seen;
  for (size_t i = 0; i < names.size(); ++i) {
    const Rgba c = ModuleColor(names, i);
    EXPECT_TRUE(seen.insert({static_cast<int>(c.r * 255), static_cast<int>(c.g * 255), static_cast<int>(c.b * 255)}).second)
        << names[i] << " repeats a colour";
    EXPECT_TRUE(c.r >= 0 && c.r <= 1 && c.g >= 0 && c.g <= 1 && c.b >= 0 && c.b <= 1);
  }
  EXPECT_EQ(ModuleColor(names, 0), color::kOrange);
  // Odometry's position does not shift the others' colours.
  const std::vector<std::string> odometry_last = {"m0", "m1", "odometry"};
  EXPECT_EQ(ModuleColor(odometry_last, 2), color::kOrange);
  EXPECT_EQ(ModuleColor(odometry_last, 1), ModuleColor(names, 2));
}

}  // namespace
}  // namespace slambox::render
