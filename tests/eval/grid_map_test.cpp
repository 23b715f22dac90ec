#include "eval/grid_map.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace slambox {
namespace {

OccupancyGrid EmptyGrid(int w, int h, double res) {
  OccupancyGrid g;
  g.origin_m = {0, 0};
  g.resolution_m = res;
  g.width = w;
  g.height = h;
  g.cells.assign(static_cast<size_t>(w) * h, -1);
  return g;
}

World OneWall() {
  World w;
  w.wall_segments.push_back({{0.05, 0.25}, {0.95, 0.25}});  // through row 2 ([0.2, 0.3)) of a 0.1 m grid
  return w;
}

TEST(GridMap, RasterizesSegmentsExactly) {
  const OccupancyGrid g = EmptyGrid(10, 10, 0.1);
  const auto mask = RasterizeWorld(OneWall(), g);
  for (int iy = 0; iy < 10; ++iy)
    for (int ix = 0; ix < 10; ++ix) EXPECT_EQ(mask[iy * 10 + ix], iy == 2 ? 1 : 0) << ix << "," << iy;
  // A diagonal through cell corners touches the diagonal cells (and corner neighbours).
  World diag;
  diag.wall_segments.push_back({{0.05, 0.05}, {0.95, 0.95}});
  const auto d = RasterizeWorld(diag, g);
  for (int k = 0; k < 10; ++k) EXPECT_EQ(d[k * 10 + k], 1);
  EXPECT_EQ(d[0 * 10 + 5], 0);
}

TEST(GridMap, RasterizesCircleBoundaryOnly) {
  const OccupancyGrid g = EmptyGrid(20, 20, 0.1);
  World w;
  w.wall_circles.push_back({{1.0, 1.0}, 0.55});
  const auto mask = RasterizeWorld(w, g);
  EXPECT_EQ(mask[10 * 20 + 15], 1);  // cell [1.5, 1.6) x [1.0, 1.1) holds (1.55, 1.0)
  EXPECT_EQ(mask[10 * 20 + 10], 0);  // the centre is inside, not on the boundary
  EXPECT_EQ(mask[10 * 20 + 17], 0);  // outside
}

TEST(GridMap, DistanceTransformMatchesBruteForce) {
  std::mt19937_64 rng(3);
  std::bernoulli_distribution occupied(0.05);
  const int w = 23, h = 17;
  std::vector<std::uint8_t> mask(w * h);
  for (auto& m : mask) m = occupied(rng);
  mask[5] = 1;
  const auto dt = DistanceTransform(mask, w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double best = std::numeric_limits<double>::infinity();
      for (int yy = 0; yy < h; ++yy)
        for (int xx = 0; xx < w; ++xx)
          if (mask[yy * w + xx]) best = std::min(best, std::hypot(x - xx, y - yy));
      EXPECT_NEAR(dt[y * w + x], best, 1e-12);
    }
  const auto none = DistanceTransform(std::vector<std::uint8_t>(12, 0), 4, 3);
  EXPECT_TRUE(std::isinf(none[0]));
}

TEST(GridMap, PerfectMapScoresZero) {
  OccupancyGrid g = EmptyGrid(10, 10, 0.1);
  const auto truth = RasterizeWorld(OneWall(), g);
  for (size_t i = 0; i < g.cells.size(); ++i) g.cells[i] = truth[i] ? 100 : 0;
  const GridMapResult r = EvaluateGridMap(g, OneWall());
  EXPECT_EQ(r.known_cells, 100);
  EXPECT_EQ(r.true_occupied, 10);
  EXPECT_EQ(r.cell_error, 0.0);
  EXPECT_EQ(r.mean_nearest_occupied_m, 0.0);
  EXPECT_EQ(r.mean_truth_to_estimate_m, 0.0);
}

TEST(GridMap, WallShiftedOneCellHandComputed) {
  OccupancyGrid g = EmptyGrid(10, 10, 0.1);
  for (int iy = 0; iy < 10; ++iy)
    for (int ix = 0; ix < 10; ++ix) g.cells[iy * 10 + ix] = iy == 3 ? 90 : (iy < 5 ? 10 : -1);
  const GridMapResult r = EvaluateGridMap(g, OneWall());
  EXPECT_EQ(r.known_cells, 50);
  EXPECT_EQ(r.estimated_occupied, 10);
  EXPECT_NEAR(r.cell_error, 20.0 / 50.0, 1e-12);  // 10 false walls + 10 missed
  EXPECT_NEAR(r.mean_nearest_occupied_m, 0.1, 1e-12);
  EXPECT_NEAR(r.mean_truth_to_estimate_m, 0.1, 1e-12);
}

TEST(GridMap, TrueOccupancyGridCoversTheWallsWithAMargin) {
  World w;
  w.wall_segments = {{{0, 0}, {4, 0}}, {{4, 0}, {4, 2}}};
  w.wall_circles = {{{1, 1}, 0.25}};
  w.landmarks = {{0, {50, 50}, 0.1}};  // not a wall: does not widen the lattice
  const OccupancyGrid g = TrueOccupancyGrid(w, 0.1, 0.5);
  EXPECT_EQ(g.origin_m, Eigen::Vector2d(-0.5, -0.5));
  EXPECT_EQ(g.width, 51);   // ceil(5.0 / 0.1) + 1
  EXPECT_EQ(g.height, 31);  // ceil(3.0 / 0.1) + 1
  ASSERT_EQ(g.cells.size(), 51u * 31u);
  for (std::int8_t c : g.cells) EXPECT_TRUE(c == 0 || c == 100);
  EXPECT_EQ(g.cells[5 * 51 + 20], 100);  // (1.55, 0.05) on the bottom wall
  EXPECT_EQ(g.cells[15 * 51 + 20], 0);   // (1.55, 1.05): 0.5 m from the circle centre, off its boundary
  const GridMapResult r = EvaluateGridMap(g, w);
  EXPECT_EQ(r.cell_error, 0.0);
  EXPECT_EQ(r.known_cells, 51 * 31);
  EXPECT_EQ(TrueOccupancyGrid(World{}).width, 0);
}

}  // namespace
}  // namespace slambox
