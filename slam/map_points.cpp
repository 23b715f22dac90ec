#include "slam/map_points.hpp"

#include <cmath>

namespace slambox {

std::vector<Eigen::Vector2d> SampleWorldOutlines(const World& world, double spacing_m) {
  std::vector<Eigen::Vector2d> out;
  for (const Segment& s : world.wall_segments) {
    const double length = (s.b - s.a).norm();
    const int n = std::max(1, static_cast<int>(std::ceil(length / spacing_m)));
    for (int i = 0; i <= n; ++i) out.push_back(s.a + (s.b - s.a) * (static_cast<double>(i) / n));
  }
  for (const Circle& c : world.wall_circles) {
    const int n = std::max(8, static_cast<int>(std::ceil(2 * M_PI * c.radius_m / spacing_m)));
    for (int i = 0; i < n; ++i) {
      const double a = 2 * M_PI * i / n;
      out.push_back(c.center + c.radius_m * Eigen::Vector2d(std::cos(a), std::sin(a)));
    }
  }
  return out;
}

}  // namespace slambox
