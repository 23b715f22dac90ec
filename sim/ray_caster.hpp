#pragma once
// Exact ray casting in double precision against the world's walls, posts and movers.
// The primitives follow b2EdgeShape / b2CircleShape / b2PolygonShape::RayCast (Box2D
// 2.4): edges are two-sided and a hit at t = 0 counts; a circle or box whose interior
// holds the ray origin is not hit. StaticGeometryIndex returns exactly what a brute-force
// minimum over all static primitives returns (same primitive, same arithmetic), found by
// walking a uniform grid with Amanatides & Woo's DDA (Eurographics 1987).
// Box2D itself computes in float: b2World::RayCast agrees with these casts on hit/miss
// and to float precision in range (~1e-4 m at 40 m, tests/sim/ray_caster_test.cpp),
// not to 1e-9; the double-precision brute force is the exact oracle.
#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "core/se2.hpp"
#include "core/world.hpp"

namespace slambox {

inline constexpr double kNoHit = std::numeric_limits<double>::infinity();

/// A segment a -> a + e with rr = |e|^2, precomputed for casting.
struct SegmentRay {
  double ax, ay, ex, ey, rr;
};
inline SegmentRay MakeSegmentRay(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const double ex = b.x() - a.x(), ey = b.y() - a.y();
  return {a.x(), a.y(), ex, ey, ex * ex + ey * ey};
}
/// b2EdgeShape::RayCast in double: intersect with the segment's line along its normal
/// n = (e.y, -e.x), then check that the hit lies between the end points (0 <= s <= 1).
inline double RaySegmentRange(const Eigen::Vector2d& o, const Eigen::Vector2d& d, double max_range_m,
                              const SegmentRay& g) {
  const double denominator = g.ey * d.x() - g.ex * d.y();
  if (denominator == 0.0 || g.rr == 0.0) return std::numeric_limits<double>::infinity();
  const double t = (g.ey * (g.ax - o.x()) - g.ex * (g.ay - o.y())) / denominator;
  if (!(t >= 0.0 && t <= max_range_m)) return std::numeric_limits<double>::infinity();
  const double s_rr = (o.x() + t * d.x() - g.ax) * g.ex + (o.y() + t * d.y() - g.ay) * g.ey;  // s |e|^2
  return (s_rr < 0.0 || s_rr > g.rr) ? std::numeric_limits<double>::infinity() : t;
}
/// Range along the unit direction `dir` to the segment, or kNoHit beyond max_range_m.
inline double RaySegmentRange(const Eigen::Vector2d& origin, const Eigen::Vector2d& dir, double max_range_m,
                              const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return RaySegmentRange(origin, dir, max_range_m, MakeSegmentRay(a, b));
}
/// Range to the entry point of the circle, or kNoHit (also when the origin is inside).
double RayCircleRange(const Eigen::Vector2d& origin, const Eigen::Vector2d& dir, double max_range_m,
                      const Eigen::Vector2d& center, double radius_m);

/// A mover's shape where it is now: a circle, or a box of full extents box_size_m.
struct MoverShape {
  SE2 T_world_mover;
  double radius_m = 0.0;
  bool is_box = false;
  Eigen::Vector2d box_size_m = Eigen::Vector2d::Zero();
};
/// Range to the closest mover, or kNoHit. A box containing the origin is not hit.
double RayMoversRange(const Eigen::Vector2d& origin, const Eigen::Vector2d& dir, double max_range_m,
                      const std::vector<MoverShape>& movers);

/// Static primitives: wall segments, wall circles and posts (landmarks are circles).
struct StaticGeometry {
  std::vector<Segment> segments;
  std::vector<Circle> circles;
};
StaticGeometry StaticGeometryOf(const World& world);
/// The oracle: minimum over every primitive.
double RayStaticRangeBruteForce(const Eigen::Vector2d& origin, const Eigen::Vector2d& dir, double max_range_m,
                                const StaticGeometry& geometry);

/// CastFan's working memory, owned by the caller: no allocation per scan once it has grown.
struct FanScratch {
  std::vector<std::uint32_t> stamp;  ///< per primitive: the fan that last collected it
  std::uint32_t fan = 0;
  std::vector<int> items;            ///< the primitives near this fan's origin
  std::vector<std::pair<double, int>> order;  ///< (distance from the origin, primitive), nearest first
};

class StaticGeometryIndex {
 public:
  /// cell_m: grid cell edge [m]; grown if the grid would exceed ~4M cells.
  explicit StaticGeometryIndex(StaticGeometry geometry, double cell_m = 2.0);
  /// Same result as RayStaticRangeBruteForce.
  double Cast(const Eigen::Vector2d& origin, const Eigen::Vector2d& dir, double max_range_m) const;
  /// A LIDAR's fan: ranges[i] = Cast(origin, dirs[i], max_range_m), bit-identical, for unit
  /// directions dirs[i] at world angle first_angle_rad + i increment_rad (increment > 0; a full
  /// circle may wrap). Each primitive within max_range_m is tested only on the beams inside its
  /// angular extent seen from the origin (padded by 1e-6 rad), nearest primitive first, and
  /// not on beams already shorter than its distance: one pass over nearby primitives instead
  /// of a cell walk per ray (sim/ray_fan.cpp).
  void CastFan(const Eigen::Vector2d& origin, double first_angle_rad, double increment_rad,
               const std::vector<Eigen::Vector2d>& dirs, double max_range_m, FanScratch& scratch,
               std::vector<double>& ranges) const;
  const StaticGeometry& geometry() const { return geometry_; }

 private:
  double TestItem(int item, const Eigen::Vector2d& origin, const Eigen::Vector2d& dir, double max_range_m) const;
  StaticGeometry geometry_;
  std::vector<SegmentRay> segment_rays_;  ///< geometry_.segments, precomputed
  Eigen::Vector2d lo_ = Eigen::Vector2d::Zero();
  double cell_m_ = 1.0;
  int nx_ = 0, ny_ = 0;
  std::vector<int> cell_start_;  ///< CSR: items of cell c are items_[cell_start_[c] .. cell_start_[c+1])
  std::vector<int> items_;       ///< < segments.size(): segment; else circle index + segments.size()
};

/// Static index plus the movers where they are now: what the LIDAR and the landmark
/// detector's line-of-sight test see (the robot itself is never part of it).
struct RayScene {
  const StaticGeometryIndex* statics = nullptr;
  std::vector<MoverShape> movers;
};
double CastRay(const RayScene& scene, const Eigen::Vector2d& origin, const Eigen::Vector2d& dir, double max_range_m);
/// CastRay when the static range along the ray is known already (from CastFan).
double CastRayPastStatics(const RayScene& scene, const Eigen::Vector2d& origin, const Eigen::Vector2d& dir,
                          double max_range_m, double statics_range_m);

}  // namespace slambox
