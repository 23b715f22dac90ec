#include "slam/occupancy_grid_builder.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace slambox {

OccupancyGrid BuildOccupancyGrid(const std::vector<SE2>& poses, const std::vector<std::vector<Eigen::Vector2d>>& scans,
                                 const OccupancyGridConfig& config) {
  OccupancyGrid grid;
  if (poses.empty()) return grid;
  Eigen::Vector2d lo = poses[0].translation(), hi = lo;
  for (size_t i = 0; i < poses.size(); ++i) {
    lo = lo.cwiseMin(poses[i].translation()), hi = hi.cwiseMax(poses[i].translation());
    for (const auto& p : scans[i]) {
      const Eigen::Vector2d w = poses[i] * p;
      lo = lo.cwiseMin(w), hi = hi.cwiseMax(w);
    }
  }
  lo.array() -= config.margin_m;
  hi.array() += config.margin_m;
  double res = config.resolution_m;
  while ((hi.x() - lo.x()) / res * (hi.y() - lo.y()) / res > config.max_cells) res *= 2;
  grid.origin_m = lo;
  grid.resolution_m = res;
  grid.width = static_cast<int>(std::ceil((hi.x() - lo.x()) / res));
  grid.height = static_cast<int>(std::ceil((hi.y() - lo.y()) / res));
  std::vector<float> log_odds(static_cast<size_t>(grid.width) * static_cast<size_t>(grid.height), 0.0f);
  std::vector<std::uint8_t> seen(log_odds.size(), 0);
  const auto add = [&](int ix, int iy, double l) {
    if (ix < 0 || iy < 0 || ix >= grid.width || iy >= grid.height) return;
    const size_t k = static_cast<size_t>(iy) * static_cast<size_t>(grid.width) + static_cast<size_t>(ix);
    log_odds[k] = static_cast<float>(std::clamp(log_odds[k] + l, -config.log_odds_clamp, config.log_odds_clamp));
    seen[k] = 1;
  };
  for (size_t i = 0; i < poses.size(); ++i) {
    const Eigen::Vector2d a = (poses[i].translation() - lo) / res;
    for (const auto& p : scans[i]) {
      const Eigen::Vector2d b = (poses[i] * p - lo) / res;
      // Amanatides-Woo traversal from cell(a) to cell(b), in grid units.
      int ix = static_cast<int>(std::floor(a.x())), iy = static_cast<int>(std::floor(a.y()));
      const int ex = static_cast<int>(std::floor(b.x())), ey = static_cast<int>(std::floor(b.y()));
      const Eigen::Vector2d d = b - a;
      const int sx = d.x() > 0 ? 1 : -1, sy = d.y() > 0 ? 1 : -1;
      const double inf = std::numeric_limits<double>::infinity();
      double t_max_x = d.x() != 0 ? ((sx > 0 ? ix + 1 - a.x() : a.x() - ix) / std::abs(d.x())) : inf;
      double t_max_y = d.y() != 0 ? ((sy > 0 ? iy + 1 - a.y() : a.y() - iy) / std::abs(d.y())) : inf;
      const double t_dx = d.x() != 0 ? 1.0 / std::abs(d.x()) : inf, t_dy = d.y() != 0 ? 1.0 / std::abs(d.y()) : inf;
      const int steps = std::abs(ex - ix) + std::abs(ey - iy);
      for (int s = 0; s < steps; ++s) {
        add(ix, iy, config.log_odds_miss);
        if (t_max_x < t_max_y) ix += sx, t_max_x += t_dx;
        else iy += sy, t_max_y += t_dy;
      }
      add(ex, ey, config.log_odds_hit);
    }
  }
  grid.cells.resize(log_odds.size());
  for (size_t k = 0; k < log_odds.size(); ++k) {
    if (!seen[k]) {
      grid.cells[k] = -1;
      continue;
    }
    const double p = 1.0 - 1.0 / (1.0 + std::exp(static_cast<double>(log_odds[k])));
    grid.cells[k] = static_cast<std::int8_t>(std::lround(100.0 * p));
  }
  return grid;
}

}  // namespace slambox
