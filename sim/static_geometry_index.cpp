// StaticGeometryIndex: a uniform grid over the static primitives, walked cell by cell
// along the ray (Amanatides & Woo 1987). Stops once the best hit lies within the cells
// already visited, so the result equals the brute-force minimum.
#include <algorithm>
#include <cmath>

#include "sim/ray_caster.hpp"

namespace slambox {

namespace {
constexpr double kPadM = 1e-7;  // cells are grown by this much when filled: hits on cell borders are kept

bool SegmentTouchesBox(const Segment& s, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  if (std::max(s.a.x(), s.b.x()) < lo.x() || std::min(s.a.x(), s.b.x()) > hi.x()) return false;
  if (std::max(s.a.y(), s.b.y()) < lo.y() || std::min(s.a.y(), s.b.y()) > hi.y()) return false;
  // Separating axis along the segment's normal: all four corners strictly on one side.
  const Eigen::Vector2d e = s.b - s.a;
  int pos = 0, neg = 0;
  for (const Eigen::Vector2d& c : {lo, hi, Eigen::Vector2d(lo.x(), hi.y()), Eigen::Vector2d(hi.x(), lo.y())}) {
    const double side = e.x() * (c.y() - s.a.y()) - e.y() * (c.x() - s.a.x());
    pos += side > 0.0;
    neg += side < 0.0;
  }
  return pos < 4 && neg < 4;
}
}  // namespace

StaticGeometryIndex::StaticGeometryIndex(StaticGeometry geometry, double cell_m)
    : geometry_(std::move(geometry)), cell_m_(cell_m) {
  for (const Segment& s : geometry_.segments) segment_rays_.push_back(MakeSegmentRay(s.a, s.b));
  const double inf = std::numeric_limits<double>::infinity();
  Eigen::Vector2d lo(inf, inf), hi(-inf, -inf);
  for (const Segment& s : geometry_.segments) {
    lo = lo.cwiseMin(s.a).cwiseMin(s.b);
    hi = hi.cwiseMax(s.a).cwiseMax(s.b);
  }
  for (const Circle& c : geometry_.circles) {
    const Eigen::Vector2d r = Eigen::Vector2d::Constant(c.radius_m);
    lo = lo.cwiseMin(c.center - r);
    hi = hi.cwiseMax(c.center + r);
  }
  if (lo.x() > hi.x()) return;  // nothing static: every cast misses
  lo_ = lo - Eigen::Vector2d::Constant(2 * kPadM);
  const Eigen::Vector2d extent = hi - lo_ + Eigen::Vector2d::Constant(2 * kPadM);
  while (std::ceil(extent.x() / cell_m_) * std::ceil(extent.y() / cell_m_) > 4e6) cell_m_ *= 2.0;
  nx_ = std::max(1, static_cast<int>(std::ceil(extent.x() / cell_m_)));
  ny_ = std::max(1, static_cast<int>(std::ceil(extent.y() / cell_m_)));

  std::vector<std::vector<int>> cells(static_cast<size_t>(nx_) * ny_);
  auto cell_range = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b, int& x0, int& x1, int& y0, int& y1) {
    x0 = std::clamp(static_cast<int>(std::floor((a.x() - kPadM - lo_.x()) / cell_m_)), 0, nx_ - 1);
    x1 = std::clamp(static_cast<int>(std::floor((b.x() + kPadM - lo_.x()) / cell_m_)), 0, nx_ - 1);
    y0 = std::clamp(static_cast<int>(std::floor((a.y() - kPadM - lo_.y()) / cell_m_)), 0, ny_ - 1);
    y1 = std::clamp(static_cast<int>(std::floor((b.y() + kPadM - lo_.y()) / cell_m_)), 0, ny_ - 1);
  };
  auto cell_box = [&](int ix, int iy, Eigen::Vector2d& a, Eigen::Vector2d& b) {
    a = lo_ + cell_m_ * Eigen::Vector2d(ix, iy) - Eigen::Vector2d::Constant(kPadM);
    b = lo_ + cell_m_ * Eigen::Vector2d(ix + 1, iy + 1) + Eigen::Vector2d::Constant(kPadM);
  };
  const int num_segments = static_cast<int>(geometry_.segments.size());
  for (int i = 0; i < num_segments; ++i) {
    const Segment& s = geometry_.segments[i];
    int x0, x1, y0, y1;
    cell_range(s.a.cwiseMin(s.b), s.a.cwiseMax(s.b), x0, x1, y0, y1);
    for (int iy = y0; iy <= y1; ++iy)
      for (int ix = x0; ix <= x1; ++ix) {
        Eigen::Vector2d a, b;
        cell_box(ix, iy, a, b);
        if (SegmentTouchesBox(s, a, b)) cells[static_cast<size_t>(iy) * nx_ + ix].push_back(i);
      }
  }
  for (int i = 0; i < static_cast<int>(geometry_.circles.size()); ++i) {
    const Circle& c = geometry_.circles[i];
    int x0, x1, y0, y1;
    const Eigen::Vector2d r = Eigen::Vector2d::Constant(c.radius_m);
    cell_range(c.center - r, c.center + r, x0, x1, y0, y1);
    for (int iy = y0; iy <= y1; ++iy)
      for (int ix = x0; ix <= x1; ++ix) cells[static_cast<size_t>(iy) * nx_ + ix].push_back(num_segments + i);
  }
  cell_start_.reserve(cells.size() + 1);
  cell_start_.push_back(0);
  for (const auto& c : cells) {
    items_.insert(items_.end(), c.begin(), c.end());
    cell_start_.push_back(static_cast<int>(items_.size()));
  }
}

double StaticGeometryIndex::TestItem(int item, const Eigen::Vector2d& o, const Eigen::Vector2d& d,
                                     double max_range_m) const {
  const int num_segments = static_cast<int>(geometry_.segments.size());
  if (item < num_segments) return RaySegmentRange(o, d, max_range_m, segment_rays_[item]);
  const Circle& c = geometry_.circles[item - num_segments];
  return RayCircleRange(o, d, max_range_m, c.center, c.radius_m);
}

double StaticGeometryIndex::Cast(const Eigen::Vector2d& o, const Eigen::Vector2d& d, double max_range_m) const {
  if (nx_ == 0) return kNoHit;
  const Eigen::Vector2d hi = lo_ + cell_m_ * Eigen::Vector2d(nx_, ny_);
  const double inf = std::numeric_limits<double>::infinity();
  const double inv_x = 1.0 / d.x(), inv_y = 1.0 / d.y();  // +-inf for an axis-parallel ray
  double t0 = 0.0, t1 = max_range_m;
  if (o.x() < lo_.x() || o.x() > hi.x() || o.y() < lo_.y() || o.y() > hi.y()) {
    // Origin outside the grid: clip the ray [0, max_range_m] to the grid's box (slab test).
    for (int a = 0; a < 2; ++a) {
      if (d[a] == 0.0) {
        if (o[a] < lo_[a] || o[a] > hi[a]) return kNoHit;
        continue;
      }
      const double inv = a == 0 ? inv_x : inv_y;
      const double ta = (lo_[a] - o[a]) * inv, tb = (hi[a] - o[a]) * inv;
      t0 = std::max(t0, std::min(ta, tb));
      t1 = std::min(t1, std::max(ta, tb));
    }
    if (t0 > t1) return kNoHit;
  }
  const double inv_cell = 1.0 / cell_m_;
  int ix = std::clamp(static_cast<int>(std::floor((o.x() + t0 * d.x() - lo_.x()) * inv_cell)), 0, nx_ - 1);
  int iy = std::clamp(static_cast<int>(std::floor((o.y() + t0 * d.y() - lo_.y()) * inv_cell)), 0, ny_ - 1);
  const int step_x = d.x() > 0 ? 1 : -1, step_y = d.y() > 0 ? 1 : -1;
  // Ray parameter where it leaves the current column / row, and its growth per cell.
  double t_max_x = d.x() == 0.0 ? inf : (lo_.x() + (ix + (d.x() > 0)) * cell_m_ - o.x()) * inv_x;
  double t_max_y = d.y() == 0.0 ? inf : (lo_.y() + (iy + (d.y() > 0)) * cell_m_ - o.y()) * inv_y;
  const double t_delta_x = d.x() == 0.0 ? inf : cell_m_ * std::abs(inv_x);
  const double t_delta_y = d.y() == 0.0 ? inf : cell_m_ * std::abs(inv_y);
  double best = kNoHit;
  while (true) {
    const size_t c = static_cast<size_t>(iy) * nx_ + ix;
    // Clipping the range to the best hit so far (as b2World::RayCast does) leaves the minimum unchanged.
    for (int k = cell_start_[c]; k < cell_start_[c + 1]; ++k)
      best = std::min(best, TestItem(items_[k], o, d, std::min(best, max_range_m)));
    const double t_exit = std::min(t_max_x, t_max_y);
    // Hits in later cells lie at t >= t_exit; the margin covers the rounding of t_exit.
    if (t_exit > t1 || best < t_exit - 1e-9 * (1.0 + t_exit)) break;
    if (t_max_x < t_max_y) {
      ix += step_x;
      if (ix < 0 || ix >= nx_) break;
      t_max_x += t_delta_x;
    } else {
      iy += step_y;
      if (iy < 0 || iy >= ny_) break;
      t_max_y += t_delta_y;
    }
  }
  return best;
}

}  // namespace slambox
