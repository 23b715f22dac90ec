#include "sim/grid_ray_cast.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace slambox {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Ray parameter [cells] at which the ray crosses the grid line `line` of one axis.
inline double Crossing(double line, double u, double d) { return (line - u) / d; }

// Entry parameter [cells] of the ray u + t d into the half-open box [lo, hi) per axis,
// or +inf when it never enters (t >= 0 only). The slab test.
double BoxEntry(const Eigen::Vector2d& u, const Eigen::Vector2d& d, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  double t0 = 0.0, t1 = kInf;
  for (int k = 0; k < 2; ++k) {
    if (d[k] == 0.0) {
      if (u[k] < lo[k] || u[k] >= hi[k]) return kInf;
      continue;
    }
    double ta = Crossing(lo[k], u[k], d[k]), tb = Crossing(hi[k], u[k], d[k]);
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 < t1 ? t0 : kInf;  // strict: grazing a corner or an edge does not enter a half-open cell
}

}  // namespace

double CastGridRay(const GridRayCaster& c, const Eigen::Vector2d& origin, const Eigen::Vector2d& dir, double max_range_m) {
  const OccupancyGrid& g = *c.grid;
  if (g.width <= 0 || g.height <= 0) return kInf;
  const double res = g.resolution_m;
  const Eigen::Vector2d u = (origin - g.origin_m) / res;  // grid frame [cells]
  const double t_max = max_range_m / res;
  double t = BoxEntry(u, dir, {0.0, 0.0}, {double(g.width), double(g.height)});
  if (!(t <= t_max)) return kInf;
  const Eigen::Vector2d p = u + t * dir;
  int ix = std::clamp(static_cast<int>(std::floor(p.x())), 0, g.width - 1);
  int iy = std::clamp(static_cast<int>(std::floor(p.y())), 0, g.height - 1);
  const int sx = dir.x() > 0 ? 1 : -1, sy = dir.y() > 0 ? 1 : -1;
  for (;;) {
    if (g.cells[static_cast<std::size_t>(iy) * g.width + ix] > c.occupied_above) return t * res;
    // Next boundary on each axis: the cell's far side in the direction of travel.
    const double tx = dir.x() == 0.0 ? kInf : Crossing(ix + (sx > 0 ? 1 : 0), u.x(), dir.x());
    const double ty = dir.y() == 0.0 ? kInf : Crossing(iy + (sy > 0 ? 1 : 0), u.y(), dir.y());
    if (tx < ty) {
      ix += sx;
      t = tx;
    } else if (ty < tx) {
      iy += sy;
      t = ty;
    } else {  // through a corner exactly: the diagonal cell is next (half-open cells are not grazed)
      ix += sx;
      iy += sy;
      t = tx;
    }
    if (ix < 0 || iy < 0 || ix >= g.width || iy >= g.height || t > t_max) return kInf;
  }
}

double CastGridRayBruteForce(const GridRayCaster& c, const Eigen::Vector2d& origin, const Eigen::Vector2d& dir,
                             double max_range_m) {
  const OccupancyGrid& g = *c.grid;
  const Eigen::Vector2d u = (origin - g.origin_m) / g.resolution_m;
  double best = kInf;
  for (int iy = 0; iy < g.height; ++iy)
    for (int ix = 0; ix < g.width; ++ix)
      if (g.cells[static_cast<std::size_t>(iy) * g.width + ix] > c.occupied_above)
        best = std::min(best, BoxEntry(u, dir, {double(ix), double(iy)}, {ix + 1.0, iy + 1.0}));
  return best * g.resolution_m <= max_range_m ? best * g.resolution_m : kInf;
}

}  // namespace slambox
