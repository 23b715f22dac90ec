#include "core/world.hpp"

#include <algorithm>
#include <limits>

namespace slambox {

Bounds WorldBounds(const World& world) {
  const double inf = std::numeric_limits<double>::infinity();
  Eigen::Vector2d lo(inf, inf), hi(-inf, -inf);
  auto add = [&](const Eigen::Vector2d& p, double r) {
    lo = lo.cwiseMin(p - Eigen::Vector2d(r, r));
    hi = hi.cwiseMax(p + Eigen::Vector2d(r, r));
  };
  for (const auto& s : world.wall_segments) { add(s.a, 0); add(s.b, 0); }
  for (const auto& c : world.wall_circles) add(c.center, c.radius_m);
  for (const auto& l : world.landmarks) add(l.position, l.radius_m);
  for (const auto& m : world.movers)
    for (const auto& p : m.path) add(p, std::max(m.radius_m, m.box_size_m.maxCoeff()));
  if (lo.x() > hi.x()) return {};
  return {lo, hi};
}

}  // namespace slambox
