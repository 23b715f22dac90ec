#include "sim/grid_ray_cast.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace slambox {
namespace {

OccupancyGrid Grid(int w, int h, double res, Eigen::Vector2d origin) {
  OccupancyGrid g;
  g.width = w;
  g.height = h;
  g.resolution_m = res;
  g.origin_m = origin;
  g.cells.assign(std::size_t(w) * h, 0);
  return g;
}

Eigen::Vector2d Dir(double a) { return {std::cos(a), std::sin(a)}; }

TEST(GridRayCast, HandComputedRanges) {
  OccupancyGrid g = Grid(10, 10, 0.5, {-1.0, -1.0});
  g.cells[4 * 10 + 7] = 100;  // cell (7, 4): x in [2.5, 3.0), y in [1.0, 1.5)
  g.cells[4 * 10 + 5] = -1;   // unknown passes
  g.cells[4 * 10 + 6] = 50;   // not above 50: free
  const GridRayCaster c(g);
  EXPECT_DOUBLE_EQ(c.Cast({0.0, 1.2}, {1, 0}, 30), 2.5);
  EXPECT_EQ(c.Cast({0.0, 1.2}, {1, 0}, 2.4), INFINITY) << "beyond max range";
  EXPECT_EQ(c.Cast({0.0, 1.2}, {-1, 0}, 30), INFINITY) << "leaves the grid";
  EXPECT_EQ(c.Cast({2.7, 1.2}, {0, 1}, 30), 0.0) << "starts inside an occupied cell";
  EXPECT_DOUBLE_EQ(c.Cast({2.7, -5.0}, {0, 1}, 30), 6.0) << "from outside the grid, y = 1.0 entry";
  EXPECT_NEAR(c.Cast({0.0, -1.5}, Dir(M_PI / 4), 30), std::sqrt(2.0) * 2.5, 1e-9) << "diagonal through cell corners";
  EXPECT_EQ(c.Cast({0.0, -1.6}, Dir(M_PI / 4), 30), c.CastBruteForce({0.0, -1.6}, Dir(M_PI / 4), 30));
  const OccupancyGrid empty;
  EXPECT_EQ(GridRayCaster(empty).Cast({0, 0}, {1, 0}, 30), INFINITY);
}

TEST(GridRayCast, MatchesBruteForceOnRandomGrids) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  int hits = 0, rays = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const int w = 5 + int(uni(rng) * 70), h = 5 + int(uni(rng) * 70);  // several 16-cell blocks
    const double res = 0.03 + 0.3 * uni(rng);
    OccupancyGrid g = Grid(w, h, res, {-10 * uni(rng), -10 * uni(rng)});
    const double fill = trial % 4 == 0 ? 0.002 : 0.02 + 0.2 * uni(rng);  // sparse: empty blocks are skipped
    for (auto& cell : g.cells) cell = uni(rng) < fill ? 100 : (uni(rng) < 0.3 ? -1 : 0);
    const GridRayCaster c(g);
    const Eigen::Vector2d lo = g.origin_m - Eigen::Vector2d(2, 2);
    const Eigen::Vector2d size = Eigen::Vector2d(w, h) * res + Eigen::Vector2d(4, 4);
    for (int k = 0; k < 500; ++k) {
      const Eigen::Vector2d o = lo + size.cwiseProduct(Eigen::Vector2d(uni(rng), uni(rng)));  // inside and outside
      Eigen::Vector2d d = Dir(2 * M_PI * uni(rng));
      if (k % 50 == 0) d = Dir(M_PI / 2 * (k / 50 % 4));  // axis-aligned rays too
      const double range = 0.5 + 20 * uni(rng);
      const double fast = c.Cast(o, d, range), oracle = c.CastBruteForce(o, d, range);
      ++rays;
      if (std::isinf(oracle)) {
        EXPECT_TRUE(std::isinf(fast)) << "trial " << trial << " ray " << k;
      } else {
        ++hits;
        EXPECT_NEAR(fast, oracle, 1e-12 * (1 + oracle)) << "trial " << trial << " ray " << k;
      }
    }
  }
  EXPECT_GT(hits, rays / 4) << "the test must exercise hits";
  EXPECT_GT(rays - hits, rays / 10) << "and misses";
}

}  // namespace
}  // namespace slambox
