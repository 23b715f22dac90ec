#include "sim/grid_contours.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

namespace slambox {
namespace {

OccupancyGrid Grid(int w, int h, const std::vector<int>& occupied, double res = 0.5) {
  OccupancyGrid g;
  g.width = w;
  g.height = h;
  g.resolution_m = res;
  g.origin_m = {1.0, -2.0};
  g.cells.assign(std::size_t(w) * h, 0);
  for (int i : occupied) g.cells[i] = 100;
  return g;
}

TEST(GridContours, SingleCellIsACounterClockwiseSquare) {
  const auto c = OccupiedContours(Grid(3, 3, {4}));
  ASSERT_EQ(c.size(), 1u);
  ASSERT_EQ(c[0].size(), 4u);
  EXPECT_DOUBLE_EQ(ContourArea(c[0]), 0.25);
  for (const auto& v : c[0]) {  // corners of cell (1, 1): x in {1.5, 2.0}, y in {-1.5, -1.0}
    EXPECT_TRUE(v.x() == 1.5 || v.x() == 2.0) << v.transpose();
    EXPECT_TRUE(v.y() == -1.5 || v.y() == -1.0) << v.transpose();
  }
}

TEST(GridContours, CollinearSidesMergeAndHolesRunClockwise) {
  // 3 x 3 block with a free centre in a 5 x 5 grid: outer square and a hole.
  std::vector<int> ring;
  for (int y = 1; y <= 3; ++y)
    for (int x = 1; x <= 3; ++x)
      if (!(x == 2 && y == 2)) ring.push_back(y * 5 + x);
  const auto c = OccupiedContours(Grid(5, 5, ring, 1.0));
  ASSERT_EQ(c.size(), 2u);
  std::multiset<double> areas;
  for (const auto& loop : c) {
    EXPECT_EQ(loop.size(), 4u);
    areas.insert(ContourArea(loop));
  }
  EXPECT_EQ(areas, (std::multiset<double>{-1.0, 9.0}));
  // Occupied up to the grid's edge closes along the edge.
  EXPECT_DOUBLE_EQ(ContourArea(OccupiedContours(Grid(2, 2, {0, 1, 2, 3}, 1.0))[0]), 4.0);
}

TEST(GridContours, DiagonalNeighboursAreSeparateLoops) {
  const auto c = OccupiedContours(Grid(2, 2, {0, 3}, 1.0));
  ASSERT_EQ(c.size(), 2u);
  EXPECT_DOUBLE_EQ(ContourArea(c[0]), 1.0);
  EXPECT_DOUBLE_EQ(ContourArea(c[1]), 1.0);
}

TEST(GridContours, RandomGridsAreaPerimeterAndLoopsTouchOnlyAtPinches) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 30; ++trial) {
    const int w = 3 + int(rng() % 30), h = 3 + int(rng() % 30);
    std::vector<int> occ;
    for (int i = 0; i < w * h; ++i)
      if (rng() % 100 < 35) occ.push_back(i);
    const OccupancyGrid g = Grid(w, h, occ, 0.25);
    auto is_occ = [&](int x, int y) { return x >= 0 && y >= 0 && x < w && y < h && g.cells[y * w + x] > 50; };
    int sides = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        if (is_occ(x, y)) sides += !is_occ(x - 1, y) + !is_occ(x + 1, y) + !is_occ(x, y - 1) + !is_occ(x, y + 1);
    double area = 0, perimeter = 0;
    for (const auto& loop : OccupiedContours(g)) {
      ASSERT_GE(loop.size(), 4u);
      area += ContourArea(loop);
      std::set<std::pair<double, double>> seen;
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const Eigen::Vector2d d = loop[(i + 1) % loop.size()] - loop[i];
        EXPECT_TRUE((d.x() == 0) != (d.y() == 0)) << "axis-aligned, non-degenerate edge";
        const Eigen::Vector2d d_next = loop[(i + 2) % loop.size()] - loop[(i + 1) % loop.size()];
        EXPECT_NE(d.x() * d_next.y() - d.y() * d_next.x(), 0.0) << "collinear edges were merged";
        perimeter += d.norm();
        if (!seen.insert({loop[i].x(), loop[i].y()}).second) {  // only where cells touch diagonally
          const int vx = int(std::lround((loop[i].x() - g.origin_m.x()) / 0.25));
          const int vy = int(std::lround((loop[i].y() - g.origin_m.y()) / 0.25));
          const bool sw = is_occ(vx - 1, vy - 1), se = is_occ(vx, vy - 1), nw = is_occ(vx - 1, vy), ne = is_occ(vx, vy);
          EXPECT_TRUE((sw && ne && !se && !nw) || (se && nw && !sw && !ne)) << "revisited vertex is not a pinch";
        }
      }
    }
    EXPECT_NEAR(area, occ.size() * 0.0625, 1e-9) << trial;  // holes subtract, outer loops add
    EXPECT_NEAR(perimeter, sides * 0.25, 1e-9) << trial;
  }
}

}  // namespace
}  // namespace slambox
