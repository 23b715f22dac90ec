#include "sim/ray_caster.hpp"

#include <gtest/gtest.h>

#include <random>

#include "sim/box2d_world.hpp"
#include "sim/lidar.hpp"

namespace slambox {
namespace {

Eigen::Vector2d Dir(double angle_rad) { return {std::cos(angle_rad), std::sin(angle_rad)}; }

Scenario KnownGeometry() {
  Scenario s;
  WallSpec seg{.kind = WallSpec::Kind::kPolyline, .points = {{5, -1}, {5, 1}}};
  WallSpec box{.kind = WallSpec::Kind::kBox, .points = {}, .center = {-10, 0}, .size = {2, 2}, .angle_deg = 45};
  WallSpec circle{.kind = WallSpec::Kind::kCircle, .points = {}, .center = {0, 7}, .radius_m = 0.5};
  WallSpec triangle{.kind = WallSpec::Kind::kPolygon, .points = {{-1, -4}, {1, -4}, {0, -6}}};
  s.walls = {seg, box, circle, triangle};
  s.robot.start = {0, 0, 0};
  return s;
}

TEST(RayCaster, KnownGeometryIsExact) {
  const World world = MakeWorld(KnownGeometry());
  ASSERT_EQ(world.wall_segments.size(), 1u + 4u + 3u);
  const StaticGeometryIndex index(StaticGeometryOf(world), 0.7);
  const Eigen::Vector2d o(0, 0);
  EXPECT_NEAR(index.Cast(o, Dir(0), 30), 5.0, 1e-9);                                 // segment, head on
  EXPECT_NEAR(index.Cast(o, Dir(std::atan2(0.5, 5.0)), 30), std::sqrt(25.25), 1e-9); // segment, oblique
  EXPECT_NEAR(index.Cast(o, Dir(M_PI), 30), 10.0 - std::sqrt(2.0), 1e-9);            // corner of a 45 deg box
  EXPECT_NEAR(index.Cast(o, Dir(M_PI / 2), 30), 6.5, 1e-9);                           // circle
  EXPECT_NEAR(index.Cast(o, Dir(-M_PI / 2), 30), 4.0, 1e-9);                          // polygon's closing edge side
  EXPECT_NEAR(index.Cast({0, -4.5}, Dir(0), 30), 0.75, 1e-9);       // inside the triangle: walls are two-sided
  EXPECT_EQ(index.Cast(o, Dir(M_PI / 4), 30), kNoHit);              // open space
  EXPECT_EQ(index.Cast(o, Dir(0), 4.9), kNoHit);                    // beyond max range
  EXPECT_EQ(index.Cast({0, 7}, Dir(0), 30), kNoHit);                // from inside a circle: not hit
}

TEST(RayCaster, MoversAreHit) {
  std::vector<MoverShape> movers(2);
  movers[0].T_world_mover = SE2(3, 0, 0);
  movers[0].radius_m = 0.3;
  movers[1].T_world_mover = SE2(0, 4, M_PI / 4);
  movers[1].is_box = true;
  movers[1].box_size_m = {1, 1};
  EXPECT_NEAR(RayMoversRange({0, 0}, Dir(0), 30, movers), 2.7, 1e-9);
  EXPECT_NEAR(RayMoversRange({0, 0}, Dir(M_PI / 2), 30, movers), 4.0 - std::sqrt(0.5), 1e-9);
  EXPECT_NEAR(RayMoversRange({0.1, 0}, Dir(M_PI / 2), 30, movers), 4.0 - std::sqrt(0.5) + 0.1, 1e-9);
  EXPECT_EQ(RayMoversRange({0, 4}, Dir(0), 30, movers), kNoHit);  // from inside the box
  const RayScene scene{nullptr, movers};
  EXPECT_NEAR(CastRay(scene, {0, 0}, Dir(0), 30), 2.7, 1e-9);
}

TEST(RayCaster, LidarIgnoresTheRobotAndReportsMissesAtMaxRange) {
  Scenario s = KnownGeometry();
  s.robot.radius_m = 0.4;
  const World world = MakeWorld(s);
  PhysicsWorld physics(s, world);
  // Box2D sees the robot disc, the reference cast skips it.
  EXPECT_NEAR(physics.RayCastBox2D({0, 0}, Dir(0), 30), 5.0, 1e-5);
  const StaticGeometryIndex index(StaticGeometryOf(world));
  LidarConfig cfg{.beams = 4, .range_max_m = 20, .sigma_range_m = 0.0};
  LidarSensor lidar(cfg, 1);
  const LaserScanEvent scan = lidar.Scan(0.0, physics.RobotPose(), RayScene{&index, {}});
  // Beams at -180, -90, 0, 90 deg.
  ASSERT_EQ(scan.ranges_m.size(), 4u);
  EXPECT_NEAR(scan.angle_min_rad, -M_PI, 1e-12);
  EXPECT_NEAR(scan.ranges_m[0], 10.0 - std::sqrt(2.0), 1e-6);  // robot pose is Box2D float
  EXPECT_NEAR(scan.ranges_m[1], 4.0, 1e-6);
  EXPECT_NEAR(scan.ranges_m[2], 5.0, 1e-6);
  EXPECT_NEAR(scan.ranges_m[3], 6.5, 1e-6);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(scan.valid[i], 1);
  cfg.range_max_m = 4.5;  // now only the -90 deg beam hits; misses are flagged, range = max
  LidarSensor short_lidar(cfg, 1);
  const LaserScanEvent s2 = short_lidar.Scan(0.0, physics.RobotPose(), RayScene{&index, {}});
  EXPECT_EQ(s2.valid[1], 1);
  for (int i : {0, 2, 3}) {
    EXPECT_EQ(s2.valid[i], 0);
    EXPECT_EQ(s2.ranges_m[i], 4.5);
  }
  cfg.range_min_m = 4.2;  // a hit closer than range_min is invalid too
  LidarSensor near_lidar(cfg, 1);
  EXPECT_EQ(near_lidar.Scan(0.0, physics.RobotPose(), RayScene{&index, {}}).valid[1], 0);
}

/// Random walls and posts in a 40 m square, plus a circle and a box mover.
Scenario RandomWorld(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-20, 20), len(0.2, 15), ang(-M_PI, M_PI), rad(0.05, 1.0);
  Scenario s;
  for (int i = 0; i < 60; ++i) {
    const Eigen::Vector2d a(u(rng), u(rng));
    s.walls.push_back({.kind = WallSpec::Kind::kPolyline, .points = {a, a + len(rng) * Dir(ang(rng))}});
  }
  for (int i = 0; i < 8; ++i) s.walls.push_back({.kind = WallSpec::Kind::kPolyline, .points = {{u(rng), 0}, {u(rng), 0}}});
  for (int i = 0; i < 10; ++i)
    s.walls.push_back({.kind = WallSpec::Kind::kBox, .points = {}, .center = {u(rng), u(rng)}, .size = {rad(rng) * 3, rad(rng)},
                       .angle_deg = ang(rng) * 57.0});
  for (int i = 0; i < 20; ++i) s.walls.push_back({.kind = WallSpec::Kind::kCircle, .points = {}, .center = {u(rng), u(rng)}, .radius_m = rad(rng)});
  for (int i = 0; i < 30; ++i) s.landmarks.push_back({{u(rng), u(rng)}, 0.1, i, 0});
  s.movers.push_back({.is_box = false, .radius_m = 0.4, .path = {{3, 3}, {6, 3}}});
  s.movers.push_back({.is_box = true, .size = {0.8, 0.5}, .path = {{-5, -5}, {-5, 5}}});
  s.robot.start = {0, 0, 0};
  s.robot.radius_m = 0.2;
  return s;
}

TEST(RayCaster, GridIndexEqualsBruteForceAndBox2D) {
  std::mt19937_64 rng(7);
  const Scenario s = RandomWorld(rng);
  const World world = MakeWorld(s);
  const StaticGeometry geometry = StaticGeometryOf(world);
  const StaticGeometryIndex index(geometry);
  PhysicsWorld physics(s, world);
  physics.Step(0.01, 0.01);  // movers leave their start points
  const RayScene scene{&index, physics.Movers()};
  std::uniform_real_distribution<double> u(-25, 25), ang(-M_PI, M_PI), range(1, 40);
  int hits = 0, box2d_mismatches = 0;
  double max_box2d_difference_m = 0.0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d o(u(rng), u(rng));
    // Every 10th ray is axis-aligned: the grid walker's degenerate case.
    const double a = i % 10 == 0 ? (i % 40) / 10 * M_PI / 2 : ang(rng);
    const Eigen::Vector2d d = Dir(a);
    const double max_range = range(rng);
    const double fast = index.Cast(o, d, max_range);
    const double brute = RayStaticRangeBruteForce(o, d, max_range, geometry);
    ASSERT_EQ(fast, brute) << "ray " << i;  // identical, not merely close
    const double full = CastRay(scene, o, d, max_range);
    const double oracle = std::min(brute, RayMoversRange(o, d, max_range, scene.movers));
    ASSERT_EQ(full, oracle);
    hits += full != kNoHit;
    // Box2D works in float: agree on hit/miss and range to float precision. Rays that
    // graze an end point within float rounding may differ; there must be almost none.
    const double ref = physics.RayCastBox2D(o, d, max_range);
    const bool agree = (ref == kNoHit && full == kNoHit) ||
                       (ref != kNoHit && full != kNoHit && std::abs(ref - full) < 2e-5 * (1 + max_range));
    box2d_mismatches += !agree;
    if (agree && full != kNoHit) max_box2d_difference_m = std::max(max_box2d_difference_m, std::abs(ref - full));
  }
  EXPECT_GT(hits, n / 4);
  EXPECT_LE(box2d_mismatches, n / 5000) << "of " << n << " rays";
  std::printf("%d of %d rays: Box2D float cast differs in hit/miss or by > 2e-5 (1 + max range); "
              "largest range difference otherwise %.2e m\n", box2d_mismatches, n, max_box2d_difference_m);
}

TEST(RayCaster, FanEqualsOneCastPerBeamBitForBit) {
  std::mt19937_64 rng(11);
  const Scenario s = RandomWorld(rng);
  const World world = MakeWorld(s);
  const StaticGeometry geometry = StaticGeometryOf(world);
  const StaticGeometryIndex index(geometry);
  std::uniform_real_distribution<double> u(-30, 30), ang(-M_PI, M_PI), range(0.5, 40);
  FanScratch scratch;
  std::vector<double> ranges;
  int fans = 0, hits = 0;
  // Full circles (the first beam at -pi, so the fan wraps through +-pi), narrow and wide fans,
  // origins outside the grid, and origins exactly on a wall segment and on a circle's rim.
  const Segment& wall = geometry.segments.at(3);
  const Circle& post = geometry.circles.at(2);
  for (int f = 0; f < 600; ++f) {
    Eigen::Vector2d o(u(rng), u(rng));
    if (f % 50 == 1) o = wall.a + 0.37 * (wall.b - wall.a);
    if (f % 50 == 2) o = wall.b;
    if (f % 50 == 3) o = post.center + post.radius_m * Eigen::Vector2d(0.6, 0.8);
    if (f % 50 == 4) o = {70.0, -3.0};
    // Within 1e-7 m of a wall (off it): the end points subtend nearly pi, where an angle error
    // that differed between opposite directions would pick the wrong way round.
    if (f % 50 == 5) o = wall.a + 0.61 * (wall.b - wall.a) + 1e-7 * Eigen::Vector2d(wall.a.y() - wall.b.y(), wall.b.x() - wall.a.x()).normalized();
    const int beams = f % 3 == 0 ? 360 : f % 3 == 1 ? 181 : 37;
    const double fov = f % 3 == 0 ? 2 * M_PI : f % 3 == 1 ? M_PI : 0.3;
    const double first = f % 3 == 0 ? -M_PI : -fov / 2, inc = f % 3 == 0 ? fov / beams : fov / (beams - 1);
    double theta = ang(rng);
    const double max_range = range(rng);
    // Every 4th fan aims one beam 5e-6 rad inside a wall's end point, seen from o: a beam a
    // culling interval too narrow for FastAtan2's error would drop (sim/ray_fan.cpp).
    if (f % 4 == 3 && f % 50 > 5) {
      const Segment& target = geometry.segments[f % geometry.segments.size()];
      const Eigen::Vector2d ta = target.a - o, tb = target.b - o;
      const double inward = ta.x() * tb.y() - ta.y() * tb.x() > 0 ? 5e-6 : -5e-6;
      const int k = beams / 2;
      theta = std::atan2(ta.y(), ta.x()) + inward - first - k * inc;
    }
    const Eigen::Matrix2d R = SE2(0, 0, theta).rotation();
    std::vector<Eigen::Vector2d> dirs;
    for (int i = 0; i < beams; ++i) dirs.push_back(R * Dir(first + i * inc));
    index.CastFan(o, theta + first, inc, dirs, max_range, scratch, ranges);
    ASSERT_EQ(ranges.size(), dirs.size());
    for (int i = 0; i < beams; ++i) {
      ASSERT_EQ(ranges[i], index.Cast(o, dirs[i], max_range)) << "fan " << f << " beam " << i;
      hits += ranges[i] != kNoHit;
    }
    ++fans;
  }
  EXPECT_GT(hits, fans * 40);
}

}  // namespace
}  // namespace slambox
