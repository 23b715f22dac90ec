// ICP's target side against brute force: the beam picked for a bearing (floor and wrap),
// the batched beam-window search (unrolled windows 0-2 and the generic path), the
// kd-tree built on first use, and ScanToPoints' cached beam directions.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "slam/icp_target.hpp"
#include "tests/support/synthetic_scan.hpp"

namespace slambox {
namespace {

// A 360-beam full circle of the room and a 100-beam, 200-degree partial scan (with misses),
// so that both the wrapped and the clamped index are exercised.
struct Targets {
  LaserScanEvent full, partial;
  IcpTarget full_target, partial_target;
};

Targets MakeTargets() {
  std::mt19937_64 rng(7);
  Targets t;
  t.full = testing::RayCastScan(testing::RoomWalls(), SE2(0.3, -0.2, 0.4), 360, 0.01, rng);
  t.partial = testing::RayCastScan(testing::RoomWalls(), SE2(-0.5, 0.1, -1.0), 100, 0.01, rng);
  t.partial.angle_increment_rad = 200.0 * M_PI / 180.0 / 100;
  for (int b = 40; b < 50; ++b) t.partial.valid[static_cast<size_t>(b)] = 0;
  t.full_target = MakeScanTarget(ScanToPoints(t.full), t.full);
  t.partial_target = MakeScanTarget(ScanToPoints(t.partial), t.partial);
  return t;
}

// Unpadded beam index in [0, beams) of beam b, or -1 outside a partial scan.
int Wrap(const IcpTarget& t, int b) {
  const int beams = static_cast<int>(t.point_of_beam.size());
  if (t.full_circle) return ((b % beams) + beams) % beams;
  return b >= 0 && b < beams ? b : -1;
}

TEST(IcpTarget, CenterBeamIsFloorOfHalfBeamShiftedIndexWrapped) {
  const Targets t = MakeTargets();
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> bearing(-M_PI, M_PI);
  for (const IcpTarget* target : {&t.full_target, &t.partial_target}) {
    const int beams = static_cast<int>(target->point_of_beam.size());
    for (int k = 0; k < 20000; ++k) {
      const double a = bearing(rng);
      double f = (a - target->angle_min_rad) * target->inverse_increment;
      if (target->full_circle && f < -0.5) f += beams;
      else if (target->full_circle && f >= beams - 0.5) f -= beams;
      ASSERT_EQ(CenterBeam(*target, a), static_cast<int>(std::floor(f + 0.5))) << a;
    }
  }
  // Beam centres and half-way points: rounding to the nearest, wrapping at +-pi.
  const IcpTarget& full = t.full_target;
  EXPECT_EQ(CenterBeam(full, full.angle_min_rad + 10.4 * full.angle_increment_rad), 10);
  EXPECT_EQ(CenterBeam(full, full.angle_min_rad + 10.6 * full.angle_increment_rad), 11);
  EXPECT_EQ(CenterBeam(full, full.angle_min_rad - 0.4 * full.angle_increment_rad), 0);
  EXPECT_EQ(CenterBeam(full, full.angle_min_rad - 0.6 * full.angle_increment_rad), 359);
  EXPECT_EQ(CenterBeam(t.partial_target, t.partial_target.angle_min_rad - 2.3 * t.partial_target.angle_increment_rad),
            -2);
}

TEST(IcpTarget, BeamWindowSearchIsBruteForceOverTheWindow) {
  const Targets t = MakeTargets();
  std::mt19937_64 rng(5);
  std::normal_distribution<double> jitter(0.0, 0.15);
  for (const IcpTarget* target : {&t.full_target, &t.partial_target}) {
    // Query points near the target's own points, plus far and behind-the-sensor ones.
    std::vector<Eigen::Vector2d> q;
    for (const Eigen::Vector2d& p : target->points) q.emplace_back(p.x() + jitter(rng), p.y() + jitter(rng));
    for (int k = 0; k < 50; ++k) q.emplace_back(20 * jitter(rng), 20 * jitter(rng));
    std::vector<double> bearing;
    for (const Eigen::Vector2d& p : q) bearing.push_back(std::atan2(p.y(), p.x()));
    for (int window = 0; window <= 4; ++window) {
      std::vector<int> nearest(q.size());
      std::vector<double> dist2(q.size());
      NearestOnBeamsBatch(*target, q.data(), bearing.data(), q.size(), window, nearest.data(), dist2.data());
      for (size_t i = 0; i < q.size(); ++i) {
        const int center = CenterBeam(*target, bearing[i]);
        int best = -1;
        double best_d2 = 0;
        for (int b = center - window; b <= center + window; ++b) {  // first strict minimum
          const int beam = Wrap(*target, b);
          const int j = beam < 0 ? -1 : target->point_of_beam[static_cast<size_t>(beam)];
          if (j < 0) continue;
          const double d2 = (target->points[static_cast<size_t>(j)] - q[i]).squaredNorm();
          if (best < 0 || d2 < best_d2) best = j, best_d2 = d2;
        }
        ASSERT_EQ(nearest[i], best) << "window " << window << " point " << i;
        if (best >= 0) {
          EXPECT_EQ(dist2[i], best_d2);
        }
        int j1 = -1;
        double d1 = 0;
        EXPECT_EQ(NearestOnBeams(*target, q[i], bearing[i], window, &j1, &d1), best >= 0);
        if (best >= 0) {
          EXPECT_EQ(j1, best);
        }
      }
    }
  }
}

TEST(IcpTarget, KdTreeOnFirstUseMatchesEagerAndBruteForce) {
  const Targets t = MakeTargets();
  const ScanPoints points = ScanToPoints(t.full);
  IcpTargetConfig eager_config;
  eager_config.build_kd_tree = true;
  const IcpTarget eager = MakeScanTarget(points, t.full, eager_config);
  const IcpTarget lazy = MakeScanTarget(points, t.full);  // default: built on the first query
  const IcpTarget copy = lazy;                            // shares the tree
  const IcpTarget cloud = MakeCloudTarget(points.points);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-4.0, 4.0);
  for (int k = 0; k < 500; ++k) {
    const Eigen::Vector2d q(u(rng), u(rng));
    int brute = 0;
    for (size_t j = 1; j < points.points.size(); ++j)
      if ((points.points[j] - q).squaredNorm() < (points.points[static_cast<size_t>(brute)] - q).squaredNorm())
        brute = static_cast<int>(j);
    for (const IcpTarget* target : {&eager, &lazy, &copy, &cloud}) {
      int j = -1;
      double d2 = 0;
      ASSERT_TRUE(NearestByKdTree(*target, q, &j, &d2));
      EXPECT_EQ(j, brute);
      EXPECT_DOUBLE_EQ(d2, (points.points[static_cast<size_t>(brute)] - q).squaredNorm());
    }
  }
}

// A local map's wall: points every 5 cm (its voxel size) with 3 cm of noise across. A line fit
// over k points spanning L has an angular error of about sigma / sqrt(sum (t - mean)^2): 11 deg
// for five points (0.2 m), 2.5 deg for all within normal_max_neighbor_m (0.6 m).
TEST(IcpTarget, CloudNormalsSpanEnoughWallToOutweighItsNoise) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0.0, 0.03);
  std::vector<Eigen::Vector2d> wall;
  for (int i = 0; i <= 200; ++i) wall.emplace_back(0.05 * i, noise(rng));
  const auto rms_tilt_deg = [&](const IcpTarget& t) {
    double sum = 0;
    int n = 0;
    for (size_t i = 10; i + 10 < t.points.size(); ++i) {  // away from the ends
      const double tilt = std::asin(std::min(1.0, std::abs(t.normals[i].x())));
      sum += tilt * tilt, ++n;
    }
    return std::sqrt(sum / n) * 180 / M_PI;
  };
  const double wide = rms_tilt_deg(MakeCloudTarget(wall));
  const double five = rms_tilt_deg(MakeCloudTarget(wall, {.normal_neighbors = 5}));
  std::printf("normal tilt RMS: %.1f deg (default), %.1f deg (five neighbours)\n", wide, five);
  EXPECT_LT(wide, 4.0);
  EXPECT_GT(five, 8.0);
}

TEST(ScanPoints, CachedDirectionsEqualDirectTrigonometryWhenGeometryChanges) {
  const Targets t = MakeTargets();
  for (const LaserScanEvent* scan : {&t.full, &t.partial, &t.full}) {  // the cache must follow the geometry
    const ScanPoints p = ScanToPoints(*scan);
    ASSERT_FALSE(p.points.empty());
    for (size_t k = 0; k < p.points.size(); ++k) {
      const size_t b = static_cast<size_t>(p.beam[k]);
      const double a = scan->angle_min_rad + static_cast<double>(b) * scan->angle_increment_rad;
      ASSERT_EQ(p.points[k].x(), scan->ranges_m[b] * std::cos(a));
      ASSERT_EQ(p.points[k].y(), scan->ranges_m[b] * std::sin(a));
    }
  }
}

}  // namespace
}  // namespace slambox
