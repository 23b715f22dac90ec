#include "slam/map_visibility.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace slambox {

namespace {

constexpr double kTwoPi = 2.0 * M_PI;

struct DepthBuffer {
  double bin_rad;
  std::vector<double> depth;  // [m] nearest wall per bin, +inf where none

  int Bin(double bearing_rad) const {
    const double u = std::fmod(bearing_rad + kTwoPi, kTwoPi) / bin_rad;
    return std::min(static_cast<int>(u), static_cast<int>(depth.size()) - 1);
  }
  double CenterOf(int bin) const { return (bin + 0.5) * bin_rad; }
};

// Distance along the unit ray u from the origin to the segment a-b (origin-relative), or
// +inf when the ray misses it: solve t u = a + s (b - a), s in [0, 1], t > 0 (Cramer).
double RayToSegment(const Eigen::Vector2d& u, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a;
  const double den = u.x() * d.y() - u.y() * d.x();  // cross(u, d)
  if (std::abs(den) < 1e-12) return std::numeric_limits<double>::infinity();
  const double t = (a.x() * d.y() - a.y() * d.x()) / den;  // cross(a, d) / cross(u, d)
  const double s = (a.x() * u.y() - a.y() * u.x()) / den;  // cross(a, u) / cross(u, d)
  return (t > 0 && s >= 0 && s <= 1) ? t : std::numeric_limits<double>::infinity();
}

// Every bin whose central ray crosses the segment a-b (origin-relative) takes its distance.
void DrawSegment(DepthBuffer& buf, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  double from = std::atan2(a.y(), a.x()), span = std::atan2(b.y(), b.x()) - from;
  span = std::remainder(span, kTwoPi);  // the segment subtends the shorter way round
  if (span < 0) from += span, span = -span;
  const int first = buf.Bin(from), bins = static_cast<int>(buf.depth.size());
  const int count = std::min(bins, static_cast<int>(std::ceil(span / buf.bin_rad)) + 2);
  for (int k = 0; k < count; ++k) {
    const int bin = (first + k) % bins;
    const double c = buf.CenterOf(bin);
    const double t = RayToSegment(Eigen::Vector2d(std::cos(c), std::sin(c)), a, b);
    buf.depth[bin] = std::min(buf.depth[bin], t);
  }
}

double DistanceToSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a;
  const double n2 = d.squaredNorm();
  const double s = n2 > 0 ? std::clamp(-a.dot(d) / n2, 0.0, 1.0) : 0.0;
  return (a + s * d).norm();
}

}  // namespace

std::vector<int> VisibleMapPoints(const World& world, const std::vector<Eigen::Vector2d>& points,
                                  const Eigen::Vector2d& origin, const MapVisibilitySetting& setting) {
  DepthBuffer buf{setting.bin_rad,
                  std::vector<double>(static_cast<size_t>(std::ceil(kTwoPi / setting.bin_rad)),
                                      std::numeric_limits<double>::infinity())};
  for (const Segment& s : world.wall_segments) {
    const Eigen::Vector2d a = s.a - origin, b = s.b - origin;
    if (DistanceToSegment(a, b) <= setting.range_max_m) DrawSegment(buf, a, b);
  }
  for (const Circle& c : world.wall_circles) {  // a post hides what lies behind its near side
    const Eigen::Vector2d v = c.center - origin;
    const double d = v.norm();
    if (d <= c.radius_m || d - c.radius_m > setting.range_max_m) continue;
    const double half = std::asin(c.radius_m / d), bearing = std::atan2(v.y(), v.x());
    const int first = buf.Bin(bearing - half), bins = static_cast<int>(buf.depth.size());
    const int count = std::min(bins, static_cast<int>(std::ceil(2 * half / buf.bin_rad)) + 1);
    for (int k = 0; k < count; ++k) buf.depth[(first + k) % bins] = std::min(buf.depth[(first + k) % bins], d - c.radius_m);
  }
  std::vector<int> seen;
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d v = points[i] - origin;
    const double r = v.norm();
    if (r > setting.range_max_m + setting.depth_margin_m) continue;
    // Hidden only when the walls of its bin and of both neighbouring bins lie in front: a
    // point beside an occluding edge (a corner, a doorway's jamb) stays, as the bins'
    // central rays may pass the edge on either side of it.
    const int b = buf.Bin(std::atan2(v.y(), v.x())), bins = static_cast<int>(buf.depth.size());
    const double depth =
        std::max({buf.depth[(b + bins - 1) % bins], buf.depth[b], buf.depth[(b + 1) % bins]});
    if (r <= depth + setting.depth_margin_m) seen.push_back(static_cast<int>(i));
  }
  return seen;
}

}  // namespace slambox
