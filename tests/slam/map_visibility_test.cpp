// The depth buffer of slam/map_visibility.hpp: walls and posts hide what lies behind them.
#include <gtest/gtest.h>

#include "slam/map_visibility.hpp"

namespace slambox {
namespace {

// A corridor's end wall at x = 1 with the outer border of a map image one metre behind
// it (x = 0), seen from (6, 0.5): the end wall is seen, the border is not; beside the
// end wall (y > 2) the border is in the open and seen.
TEST(MapVisibility, AWallHidesTheSurfaceBehindIt) {
  World w;
  w.wall_segments = {{{1, -1}, {1, 2}}, {{0, -5}, {0, 5}}};
  const std::vector<Eigen::Vector2d> points = {{1, 0.5}, {1, -0.9}, {0, 0.5}, {0, -0.5}, {0, 4.5}, {0.8, 0.5}};
  const std::vector<int> seen = VisibleMapPoints(w, points, {6, 0.5}, {});
  EXPECT_EQ(seen, (std::vector<int>{0, 1, 4, 5}));  // (0.8, 0.5) lies within the 0.3 m margin
  MapVisibilitySetting thin;
  thin.depth_margin_m = 0.1;
  EXPECT_EQ(VisibleMapPoints(w, points, {6, 0.5}, thin), (std::vector<int>{0, 1, 4}));
}

// A post of radius 0.5 at (3, 0) hides the wall point straight behind it, not the one
// off to the side; range_max_m drops far points.
TEST(MapVisibility, PostsOccludeAndRangeLimits) {
  World w;
  w.wall_segments = {{{6, -5}, {6, 5}}};
  w.wall_circles = {{{3, 0}, 0.5}};
  const std::vector<Eigen::Vector2d> points = {{6, 0}, {6, 3}, {2.5, 0}};
  EXPECT_EQ(VisibleMapPoints(w, points, {0, 0}, {}), (std::vector<int>{1, 2}));
  MapVisibilitySetting near;
  near.range_max_m = 5.0;
  EXPECT_EQ(VisibleMapPoints(w, points, {0, 0}, near), (std::vector<int>{2}));
}

// A wall that wraps across the bearing +-pi (behind the sensor) still occludes.
TEST(MapVisibility, WallsAcrossTheBearingWrap) {
  World w;
  w.wall_segments = {{{-2, -3}, {-2, 3}}};
  const std::vector<Eigen::Vector2d> points = {{-2, 0.01}, {-2, -0.01}, {-3, 0.01}, {-3, -0.01}};
  EXPECT_EQ(VisibleMapPoints(w, points, {0, 0}, {}), (std::vector<int>{0, 1}));
}

}  // namespace
}  // namespace slambox
