// Module colours: a baseline module (ModuleInfo::baseline, e.g. odometry) is always
// orange, and the registry's modules (plus room to grow) get distinct colours, the same for
// a module wherever the baseline sits.
#include "render/palette.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <tuple>

namespace slambox::render {
namespace {

TEST(Palette, FifteenModulesBesidesTheBaselineGetDistinctColours) {
  std::vector<bool> baseline = {true};
  for (int i = 0; i < 15; ++i) baseline.push_back(false);
  std::set<std::tuple<int, int, int>> seen;
  for (size_t i = 0; i < baseline.size(); ++i) {
    const Rgba c = ModuleColor(baseline, i);
    EXPECT_TRUE(seen.insert({static_cast<int>(c.r * 255), static_cast<int>(c.g * 255), static_cast<int>(c.b * 255)}).second)
        << "module " << i << " repeats a colour";
    EXPECT_TRUE(c.r >= 0 && c.r <= 1 && c.g >= 0 && c.g <= 1 && c.b >= 0 && c.b <= 1);
  }
  EXPECT_EQ(ModuleColor(baseline, 0), color::kOrange);
  // The baseline's position does not shift the others' colours.
  const std::vector<bool> baseline_last = {false, false, true};
  EXPECT_EQ(ModuleColor(baseline_last, 2), color::kOrange);
  EXPECT_EQ(ModuleColor(baseline_last, 1), ModuleColor(baseline, 2));
  // Without a baseline no module is orange.
  const std::vector<bool> none(6, false);
  for (size_t i = 0; i < none.size(); ++i) EXPECT_NE(ModuleColor(none, i), color::kOrange) << i;
}

}  // namespace
}  // namespace slambox::render
