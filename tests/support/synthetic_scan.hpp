#pragma once
// Test/bench support: one LIDAR scan of wall segments by exact ray casting, with Gaussian
// range noise from the caller's generator, and a few simple worlds.
#include <cmath>
#include <random>
#include <vector>

#include "core/stream.hpp"
#include "core/world.hpp"

namespace slambox::testing {

inline LaserScanEvent RayCastScan(const std::vector<Segment>& walls, const SE2& pose, int beams, double sigma_m,
                                  std::mt19937_64& rng, double range_max_m = 30.0, double t_s = 0.0) {
  std::normal_distribution<double> n01(0.0, 1.0);
  LaserScanEvent scan;
  scan.t_s = t_s;
  scan.angle_increment_rad = 2 * M_PI / beams;
  scan.angle_min_rad = -M_PI;
  scan.range_min_m = 0.1;
  scan.range_max_m = range_max_m;
  for (int b = 0; b < beams; ++b) {
    const double a = pose.theta + scan.angle_min_rad + b * scan.angle_increment_rad;
    const Eigen::Vector2d dir(std::cos(a), std::sin(a)), o = pose.translation();
    double best = range_max_m;
    for (const auto& seg : walls) {  // o + r dir = a + u (b - a)
      const Eigen::Vector2d e = seg.b - seg.a;
      const double den = -dir.x() * e.y() + dir.y() * e.x();
      if (std::abs(den) < 1e-12) continue;
      const Eigen::Vector2d rhs = seg.a - o;
      const double r = (-rhs.x() * e.y() + rhs.y() * e.x()) / den;
      const double u = (dir.x() * rhs.y() - dir.y() * rhs.x()) / den;
      if (r > 0 && u >= 0 && u <= 1 && r < best) best = r;
    }
    const bool hit = best < range_max_m && best >= scan.range_min_m;
    scan.ranges_m.push_back(hit ? best + sigma_m * n01(rng) : range_max_m);
    scan.valid.push_back(hit ? 1 : 0);
  }
  return scan;
}

inline std::vector<Segment> Polyline(const std::vector<Eigen::Vector2d>& p, bool closed) {
  std::vector<Segment> s;
  for (size_t i = 0; i + 1 < p.size(); ++i) s.push_back({p[i], p[i + 1]});
  if (closed) s.push_back({p.back(), p.front()});
  return s;
}

/// An 8 m x 6 m room with a pillar box and an alcove, centred near the origin.
inline std::vector<Segment> RoomWalls() {
  auto w = Polyline({{-4, -3}, {4, -3}, {4, 1}, {5, 1}, {5, 2}, {4, 2}, {4, 3}, {-4, 3}}, true);
  auto box = Polyline({{1, 0.5}, {1.6, 0.5}, {1.6, 1.1}, {1, 1.1}}, true);
  w.insert(w.end(), box.begin(), box.end());
  return w;
}

/// A featureless corridor 2 m wide along x, 60 m long, closed at neither end within range.
inline std::vector<Segment> CorridorWalls() {
  return {{{-30, -1}, {30, -1}}, {{-30, 1}, {30, 1}}};
}

}  // namespace slambox::testing
