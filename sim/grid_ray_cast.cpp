#include "sim/grid_ray_cast.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace slambox {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Ray parameter [cells] at which the ray crosses the grid line `line` of one axis.
inline double Crossing(double line, double u, double d) { return (line - u) / d; }

// Entry parameter [cells] of the ray u + t d (t >= 0) into the half-open box [lo, hi),
// or +inf when it never enters. The slab test.
double BoxEntry(const Eigen::Vector2d& u, const Eigen::Vector2d& d, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                double* exit = nullptr) {
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
  if (exit) *exit = t1;
  return t0 < t1 ? t0 : kInf;  // strict: grazing a corner or an edge does not enter a half-open cell
}

// One Amanatides-Woo walk over a lattice of cells of side `size` [cells], from cell
// (ix, iy) entered at t, within [x_lo, x_hi) x [y_lo, y_hi) (lattice indices). Calls
// visit(ix, iy, t) for each cell; stops when visit returns true (returns t) or the walk
// leaves the range or t > t_max (returns +inf).
template <typename Visit>
double Walk(const Eigen::Vector2d& u, const Eigen::Vector2d& d, int size, int ix, int iy, double t, int x_lo, int x_hi,
            int y_lo, int y_hi, double t_max, Visit visit) {
  const int sx = d.x() > 0 ? 1 : -1, sy = d.y() > 0 ? 1 : -1;
  for (;;) {
    if (visit(ix, iy, t)) return t;
    const double tx = d.x() == 0.0 ? kInf : Crossing(double(ix + (sx > 0 ? 1 : 0)) * size, u.x(), d.x());
    const double ty = d.y() == 0.0 ? kInf : Crossing(double(iy + (sy > 0 ? 1 : 0)) * size, u.y(), d.y());
    if (tx < ty) {
      ix += sx;
      t = tx;
    } else if (ty < tx) {
      iy += sy;
      t = ty;
    } else {  // exactly through a corner: the diagonal cell is next (half-open cells are not grazed)
      ix += sx;
      iy += sy;
      t = tx;
    }
    if (ix < x_lo || iy < y_lo || ix >= x_hi || iy >= y_hi || t > t_max) return kInf;
  }
}

}  // namespace

GridRayCaster::GridRayCaster(const OccupancyGrid& grid, int occupied_above)
    : grid_(&grid), width_(grid.width), height_(grid.height) {
  if (width_ <= 0 || height_ <= 0) return;
  blocks_x_ = (width_ + kBlock - 1) / kBlock;
  blocks_y_ = (height_ + kBlock - 1) / kBlock;
  occupied_.resize(grid.cells.size());
  block_occupied_.assign(static_cast<std::size_t>(blocks_x_) * blocks_y_, 0);
  for (int iy = 0; iy < height_; ++iy)
    for (int ix = 0; ix < width_; ++ix) {
      const std::size_t i = static_cast<std::size_t>(iy) * width_ + ix;
      occupied_[i] = grid.cells[i] > occupied_above;
      if (occupied_[i]) block_occupied_[static_cast<std::size_t>(iy / kBlock) * blocks_x_ + ix / kBlock] = 1;
    }
}

double GridRayCaster::Cast(const Eigen::Vector2d& origin, const Eigen::Vector2d& dir, double max_range_m) const {
  if (width_ <= 0 || height_ <= 0) return kInf;
  const double res = grid_->resolution_m;
  const Eigen::Vector2d u = (origin - grid_->origin_m) / res;  // grid frame [cells]
  const double t_max = max_range_m / res;
  double t_exit = kInf;
  const double t0 = BoxEntry(u, dir, {0.0, 0.0}, {double(width_), double(height_)}, &t_exit);
  if (!(t0 <= t_max)) return kInf;
  // A partial last block reaches past the grid: stop the block walk where the ray leaves it.
  const double t_blocks = std::min(t_max, t_exit);
  const Eigen::Vector2d p = u + t0 * dir;
  const int cx = std::clamp(static_cast<int>(std::floor(p.x())), 0, width_ - 1);
  const int cy = std::clamp(static_cast<int>(std::floor(p.y())), 0, height_ - 1);
  double hit = kInf;
  Walk(u, dir, kBlock, cx / kBlock, cy / kBlock, t0, 0, blocks_x_, 0, blocks_y_, t_blocks, [&](int bx, int by, double t) {
    if (!block_occupied_[static_cast<std::size_t>(by) * blocks_x_ + bx]) return false;
    // Inside an occupied block: walk its cells from where the ray entered it.
    const int x_lo = bx * kBlock, y_lo = by * kBlock;
    const int x_hi = std::min(x_lo + kBlock, width_), y_hi = std::min(y_lo + kBlock, height_);
    const Eigen::Vector2d q = u + t * dir;
    const int ix = std::clamp(static_cast<int>(std::floor(q.x())), x_lo, x_hi - 1);
    const int iy = std::clamp(static_cast<int>(std::floor(q.y())), y_lo, y_hi - 1);
    hit = Walk(u, dir, 1, ix, iy, t, x_lo, x_hi, y_lo, y_hi, t_max,
               [&](int x, int y, double) { return Occupied(x, y); });
    return hit < kInf;
  });
  return hit < kInf ? hit * res : kInf;
}

double GridRayCaster::CastBruteForce(const Eigen::Vector2d& origin, const Eigen::Vector2d& dir,
                                     double max_range_m) const {
  const Eigen::Vector2d u = (origin - grid_->origin_m) / grid_->resolution_m;
  double best = kInf;
  for (int iy = 0; iy < height_; ++iy)
    for (int ix = 0; ix < width_; ++ix)
      if (Occupied(ix, iy)) best = std::min(best, BoxEntry(u, dir, {double(ix), double(iy)}, {ix + 1.0, iy + 1.0}));
  return best * grid_->resolution_m <= max_range_m ? best * grid_->resolution_m : kInf;
}

}  // namespace slambox
