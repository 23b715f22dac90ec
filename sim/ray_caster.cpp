#include "sim/ray_caster.hpp"

#include <algorithm>
#include <cmath>

namespace slambox {

double RayCircleRange(const Eigen::Vector2d& o, const Eigen::Vector2d& d, double max_range_m,
                      const Eigen::Vector2d& center, double radius_m) {
  // |o + t d - c|^2 = r^2 with |d| = 1: t = -(c' + sqrt(c'^2 - b)), c' = s.d, b = s.s - r^2.
  const Eigen::Vector2d s = o - center;
  const double b = s.squaredNorm() - radius_m * radius_m;
  const double c = s.dot(d);
  const double sigma = c * c - b;
  if (sigma < 0.0) return kNoHit;
  const double t = -(c + std::sqrt(sigma));
  return (t >= 0.0 && t <= max_range_m) ? t : kNoHit;
}

namespace {
/// b2PolygonShape::RayCast on the box [-h, h] in the box frame: clip the ray against each
/// face's half-plane; a hit needs an entering face (origin outside).
double RayBoxRange(const Eigen::Vector2d& o, const Eigen::Vector2d& d, double max_range_m, const Eigen::Vector2d& h) {
  static const double kNormals[4][2] = {{0, -1}, {1, 0}, {0, 1}, {-1, 0}};
  double lower = 0.0, upper = max_range_m;
  bool entered = false;
  for (const auto& nrm : kNormals) {
    const Eigen::Vector2d n(nrm[0], nrm[1]);
    const double numerator = std::abs(nrm[0]) * h.x() + std::abs(nrm[1]) * h.y() - n.dot(o);
    const double denominator = n.dot(d);
    if (denominator == 0.0) {
      if (numerator < 0.0) return kNoHit;
    } else if (denominator < 0.0 && numerator < lower * denominator) {
      lower = numerator / denominator;
      entered = true;
    } else if (denominator > 0.0 && numerator < upper * denominator) {
      upper = numerator / denominator;
    }
    if (upper < lower) return kNoHit;
  }
  return entered ? lower : kNoHit;
}
}  // namespace

double RayMoversRange(const Eigen::Vector2d& o, const Eigen::Vector2d& d, double max_range_m,
                      const std::vector<MoverShape>& movers) {
  double best = kNoHit;
  for (const MoverShape& m : movers) {
    // Cheap rejection: the ray passes outside the mover's bounding circle or behind it.
    const Eigen::Vector2d to_center = m.T_world_mover.translation() - o;
    const double bound_sq = m.is_box ? 0.25 * m.box_size_m.squaredNorm() : m.radius_m * m.radius_m;
    const double along = to_center.dot(d);
    if (to_center.squaredNorm() - along * along > bound_sq * (1.0 + 1e-9) ||
        (along < 0.0 && to_center.squaredNorm() > bound_sq)) {
      continue;
    }
    double t;
    if (m.is_box) {
      const SE2 T_mover_world = m.T_world_mover.inverse();
      const Eigen::Vector2d d_m = T_mover_world.rotation() * d;
      t = RayBoxRange(T_mover_world * o, d_m, max_range_m, m.box_size_m / 2.0);
    } else {
      t = RayCircleRange(o, d, max_range_m, m.T_world_mover.translation(), m.radius_m);
    }
    best = std::min(best, t);
  }
  return best;
}

StaticGeometry StaticGeometryOf(const World& world) {
  StaticGeometry g;
  g.segments = world.wall_segments;
  g.circles = world.wall_circles;
  for (const TrueLandmark& lm : world.landmarks) g.circles.push_back({lm.position, lm.radius_m});
  return g;
}

double RayStaticRangeBruteForce(const Eigen::Vector2d& o, const Eigen::Vector2d& d, double max_range_m,
                                const StaticGeometry& g) {
  double best = kNoHit;
  for (const Segment& s : g.segments) best = std::min(best, RaySegmentRange(o, d, max_range_m, s.a, s.b));
  for (const Circle& c : g.circles) best = std::min(best, RayCircleRange(o, d, max_range_m, c.center, c.radius_m));
  return best;
}

double CastRayPastStatics(const RayScene& scene, const Eigen::Vector2d& o, const Eigen::Vector2d& d,
                          double max_range_m, double statics) {
  if (scene.movers.empty()) return statics;
  return std::min(statics, RayMoversRange(o, d, std::min(max_range_m, statics), scene.movers));
}

double CastRay(const RayScene& scene, const Eigen::Vector2d& o, const Eigen::Vector2d& d, double max_range_m) {
  const double statics = scene.statics ? scene.statics->Cast(o, d, max_range_m) : kNoHit;
  return CastRayPastStatics(scene, o, d, max_range_m, statics);
}

}  // namespace slambox
