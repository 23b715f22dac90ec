#include "eval/grid_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace slambox {

namespace {
// Liang-Barsky clipping: does segment a-b meet the closed box [lo, hi]?
bool SegmentHitsBox(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& lo,
                    const Eigen::Vector2d& hi) {
  double t0 = 0.0, t1 = 1.0;
  const Eigen::Vector2d d = b - a;
  for (int k = 0; k < 2; ++k) {
    if (d[k] == 0.0) {
      if (a[k] < lo[k] || a[k] > hi[k]) return false;
      continue;
    }
    double ta = (lo[k] - a[k]) / d[k], tb = (hi[k] - a[k]) / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

// 1D squared distance transform of f (Felzenszwalb & Huttenlocher 2012, Algorithm 1):
// lower envelope of parabolas rooted at every q with height f(q).
void Transform1D(const std::vector<double>& f, std::vector<double>& d) {
  const int n = static_cast<int>(f.size());
  std::vector<int> v(n);
  std::vector<double> z(n + 1);
  int k = 0;
  v[0] = 0;
  z[0] = -std::numeric_limits<double>::infinity();
  z[1] = std::numeric_limits<double>::infinity();
  for (int q = 1; q < n; ++q) {
    auto intersection = [&](int p) { return ((f[q] + double(q) * q) - (f[p] + double(p) * p)) / (2.0 * q - 2.0 * p); };
    double s = intersection(v[k]);
    while (s <= z[k]) s = intersection(v[--k]);  // z[0] = -inf ends the loop
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = std::numeric_limits<double>::infinity();
  }
  k = 0;
  d.assign(n, 0.0);
  for (int q = 0; q < n; ++q) {
    while (z[k + 1] < q) ++k;
    d[q] = double(q - v[k]) * (q - v[k]) + f[v[k]];
  }
}
}  // namespace

std::vector<std::uint8_t> RasterizeWorld(const World& world, const OccupancyGrid& g) {
  std::vector<std::uint8_t> mask(static_cast<size_t>(g.width) * g.height, 0);
  const double res = g.resolution_m;
  auto cell_range = [&](Eigen::Vector2d lo, Eigen::Vector2d hi, int& x0, int& y0, int& x1, int& y1) {
    x0 = std::max(0, static_cast<int>(std::floor((lo.x() - g.origin_m.x()) / res)));
    y0 = std::max(0, static_cast<int>(std::floor((lo.y() - g.origin_m.y()) / res)));
    x1 = std::min(g.width - 1, static_cast<int>(std::floor((hi.x() - g.origin_m.x()) / res)));
    y1 = std::min(g.height - 1, static_cast<int>(std::floor((hi.y() - g.origin_m.y()) / res)));
  };
  auto box = [&](int ix, int iy, Eigen::Vector2d& lo, Eigen::Vector2d& hi) {
    lo = g.origin_m + Eigen::Vector2d(ix, iy) * res;
    hi = lo + Eigen::Vector2d(res, res);
  };
  for (const auto& s : world.wall_segments) {
    int x0, y0, x1, y1;
    cell_range(s.a.cwiseMin(s.b), s.a.cwiseMax(s.b), x0, y0, x1, y1);
    for (int iy = y0; iy <= y1; ++iy)
      for (int ix = x0; ix <= x1; ++ix) {
        Eigen::Vector2d lo, hi;
        box(ix, iy, lo, hi);
        if (SegmentHitsBox(s.a, s.b, lo, hi)) mask[static_cast<size_t>(iy) * g.width + ix] = 1;
      }
  }
  for (const auto& c : world.wall_circles) {
    const Eigen::Vector2d r(c.radius_m, c.radius_m);
    int x0, y0, x1, y1;
    cell_range(c.center - r, c.center + r, x0, y0, x1, y1);
    for (int iy = y0; iy <= y1; ++iy)
      for (int ix = x0; ix <= x1; ++ix) {
        Eigen::Vector2d lo, hi;
        box(ix, iy, lo, hi);
        const double near = (c.center.cwiseMax(lo).cwiseMin(hi) - c.center).norm();
        const Eigen::Vector2d far_corner((c.center.x() - lo.x() > hi.x() - c.center.x()) ? lo.x() : hi.x(),
                                         (c.center.y() - lo.y() > hi.y() - c.center.y()) ? lo.y() : hi.y());
        const double far = (far_corner - c.center).norm();
        if (near <= c.radius_m && c.radius_m <= far) mask[static_cast<size_t>(iy) * g.width + ix] = 1;
      }
  }
  return mask;
}

OccupancyGrid TrueOccupancyGrid(const World& world, double resolution_m, double margin_m) {
  OccupancyGrid g;
  g.resolution_m = resolution_m;
  if (world.wall_segments.empty() && world.wall_circles.empty()) return g;
  World walls;  // landmarks and mover paths do not widen the lattice
  walls.wall_segments = world.wall_segments;
  walls.wall_circles = world.wall_circles;
  const Bounds b = WorldBounds(walls);
  const Eigen::Vector2d margin(margin_m, margin_m);
  g.origin_m = b.min - margin;
  g.width = static_cast<int>(std::ceil((b.max.x() - b.min.x() + 2 * margin_m) / resolution_m)) + 1;
  g.height = static_cast<int>(std::ceil((b.max.y() - b.min.y() + 2 * margin_m) / resolution_m)) + 1;
  const std::vector<std::uint8_t> mask = RasterizeWorld(world, g);
  g.cells.resize(mask.size());
  for (size_t i = 0; i < mask.size(); ++i) g.cells[i] = mask[i] ? 100 : 0;
  return g;
}

std::vector<double> DistanceTransform(const std::vector<std::uint8_t>& mask, int w, int h) {
  const double inf = std::numeric_limits<double>::infinity();
  if (std::none_of(mask.begin(), mask.end(), [](std::uint8_t m) { return m != 0; }))
    return std::vector<double>(mask.size(), inf);
  const double big = 1e20;  // finite "infinity" keeps the parabola arithmetic defined
  std::vector<double> sq(mask.size()), f, d;
  for (size_t i = 0; i < mask.size(); ++i) sq[i] = mask[i] ? 0.0 : big;
  f.resize(h);
  for (int x = 0; x < w; ++x) {  // columns, then rows (separability)
    for (int y = 0; y < h; ++y) f[y] = sq[static_cast<size_t>(y) * w + x];
    Transform1D(f, d);
    for (int y = 0; y < h; ++y) sq[static_cast<size_t>(y) * w + x] = d[y];
  }
  f.resize(w);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) f[x] = sq[static_cast<size_t>(y) * w + x];
    Transform1D(f, d);
    for (int x = 0; x < w; ++x) sq[static_cast<size_t>(y) * w + x] = std::sqrt(d[x]);
  }
  return sq;
}

GridMapResult EvaluateGridMap(const OccupancyGrid& g, const World& world, const GridMapOptions& o) {
  GridMapResult r;
  const std::vector<std::uint8_t> truth = RasterizeWorld(world, g);
  std::vector<std::uint8_t> est(truth.size(), 0);
  int wrong = 0;
  for (size_t i = 0; i < truth.size() && i < g.cells.size(); ++i) {
    r.true_occupied += truth[i];
    if (g.cells[i] < 0) continue;
    const bool occupied = g.cells[i] > o.occupied_above;
    est[i] = occupied ? 1 : 0;
    ++r.known_cells;
    r.estimated_occupied += occupied;
    wrong += occupied != (truth[i] != 0);
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  r.cell_error = r.known_cells ? static_cast<double>(wrong) / r.known_cells : nan;
  auto mean_distance = [&](const std::vector<std::uint8_t>& from, const std::vector<std::uint8_t>& to) {
    const std::vector<double> dt = DistanceTransform(to, g.width, g.height);
    double sum = 0.0;
    int n = 0;
    for (size_t i = 0; i < from.size(); ++i)
      if (from[i]) {
        sum += dt[i];
        ++n;
      }
    return (n == 0 || !std::isfinite(sum)) ? nan : sum / n * g.resolution_m;
  };
  r.mean_nearest_occupied_m = mean_distance(est, truth);
  r.mean_truth_to_estimate_m = mean_distance(truth, est);
  return r;
}

}  // namespace slambox
