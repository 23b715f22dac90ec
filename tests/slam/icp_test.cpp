// ICP recovers known motions for every variant, forward and inverse; projection and
// kd-tree agree; degeneracy is flagged in a corridor and not in a room.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cstdio>
#include <random>

#include "slam/icp.hpp"
#include "tests/support/synthetic_scan.hpp"

namespace slambox {
namespace {

using testing::CorridorWalls;
using testing::RayCastScan;
using testing::RoomWalls;

struct Variant {
  IcpMetric metric;
  IcpCorrespondence corr;
  const char* name;
};
const Variant kVariants[] = {
    {IcpMetric::kPointToPoint, IcpCorrespondence::kKdTree, "p2p-kdtree"},
    {IcpMetric::kPointToPoint, IcpCorrespondence::kProjection, "p2p-projection"},
    {IcpMetric::kPointToLine, IcpCorrespondence::kKdTree, "p2l-kdtree"},
    {IcpMetric::kPointToLine, IcpCorrespondence::kProjection, "p2l-projection"},
};

IcpConfig ConfigFor(const Variant& v) {
  IcpConfig c;
  c.metric = v.metric;
  c.correspondence = v.corr;
  c.max_iterations = v.metric == IcpMetric::kPointToPoint ? 100 : 30;
  c.convergence_translation_m = 1e-6;
  c.convergence_rotation_rad = 1e-6;
  return c;
}

struct ScanPair {
  ScanPoints source;
  IcpTarget target;
};

// Target scan at pose A, source at B = A * T_target_source.
ScanPair MakePair(const std::vector<Segment>& walls, const SE2& A, const SE2& T_ts, double sigma_m,
                  std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const LaserScanEvent scan_a = RayCastScan(walls, A, 360, sigma_m, rng);
  const LaserScanEvent scan_b = RayCastScan(walls, A * T_ts, 360, sigma_m, rng);
  return {ScanToPoints(scan_b), MakeScanTarget(ScanToPoints(scan_a), scan_a)};
}

TEST(Icp, RecoversKnownMotionForEveryVariantForwardAndInverse) {
  const SE2 A(-0.5, -0.3, 0.2);
  const SE2 T_true(0.16, 0.05, 3.0 * M_PI / 180);
  const SE2 starts[] = {SE2(), SE2(0.25, -0.1, 0.0), SE2(0.05, 0.15, 0.08), SE2(0.3, 0.1, -0.05)};
  for (const Variant& v : kVariants) {
    for (bool inverse : {false, true}) {
      const SE2 T = inverse ? T_true.inverse() : T_true;
      const ScanPair pair = MakePair(RoomWalls(), inverse ? A * T_true : A, T, 0.0, 1);
      for (const SE2& s : starts) {
        const SE2 start = inverse ? s.inverse() : s;
        const IcpResult r = RegisterIcp(pair.source.points, pair.target, start, ConfigFor(v));
        // p2p on a sampled scan has a bias of a fraction of the beam spacing; p2l is exact
        // up to the PCA normals of a polygon's corners.
        const double tol_m = v.metric == IcpMetric::kPointToPoint ? 0.02 : 2e-3;
        EXPECT_TRUE(r.converged) << v.name;
        EXPECT_NEAR(r.T_target_source.x, T.x, tol_m) << v.name << " inverse=" << inverse;
        EXPECT_NEAR(r.T_target_source.y, T.y, tol_m) << v.name << " inverse=" << inverse;
        EXPECT_NEAR(NormalizeAngle(r.T_target_source.theta - T.theta), 0.0, tol_m / 2) << v.name;
        EXPECT_FALSE(r.degenerate) << v.name;
        EXPECT_GT(r.num_inliers, 250) << v.name;
      }
    }
  }
}

TEST(Icp, PointToLineIsAccurateWithRangeNoise) {
  for (std::uint64_t seed = 0; seed < 5; ++seed) {
    const SE2 T_true(0.16, -0.04, -3.0 * M_PI / 180);
    const ScanPair pair = MakePair(RoomWalls(), SE2(0.2, 0.1, 1.0), T_true, 0.01, seed);
    IcpConfig c = ConfigFor(kVariants[3]);
    c.convergence_translation_m = IcpConfig{}.convergence_translation_m;  // noise: 1e-6 flips pairs forever
    c.convergence_rotation_rad = IcpConfig{}.convergence_rotation_rad;
    const IcpResult r = RegisterIcp(pair.source.points, pair.target, SE2(), c);
    EXPECT_TRUE(r.converged);
    EXPECT_LT((r.T_target_source.translation() - T_true.translation()).norm(), 0.005);
    EXPECT_LT(std::abs(NormalizeAngle(r.T_target_source.theta - T_true.theta)), 0.002);
    EXPECT_NEAR(r.rms_residual_m, 0.01, 0.006);  // about the range noise
    // The covariance is positive definite and (optimistically) sub-centimetre.
    EXPECT_GT(r.covariance.determinant(), 0.0);
    EXPECT_LT(std::sqrt(r.covariance(0, 0)), 0.01);
  }
}

TEST(Icp, ProjectionAndKdTreeAgreeOnCleanData) {
  const SE2 T_true(0.1, 0.08, 0.04);
  const ScanPair pair = MakePair(RoomWalls(), SE2(0.3, -0.2, -0.7), T_true, 0.0, 4);
  for (IcpMetric m : {IcpMetric::kPointToPoint, IcpMetric::kPointToLine}) {
    IcpConfig c = ConfigFor({m, IcpCorrespondence::kKdTree, ""});
    const IcpResult a = RegisterIcp(pair.source.points, pair.target, SE2(), c);
    c.correspondence = IcpCorrespondence::kProjection;
    const IcpResult b = RegisterIcp(pair.source.points, pair.target, SE2(), c);
    EXPECT_NEAR(a.T_target_source.x, b.T_target_source.x, 2e-3);
    EXPECT_NEAR(a.T_target_source.y, b.T_target_source.y, 2e-3);
    EXPECT_NEAR(a.T_target_source.theta, b.T_target_source.theta, 1e-3);
  }
}

TEST(Icp, DegeneracyDetectedInCorridorAndNotInRoom) {
  const SE2 T_true(0.3, 0.02, 0.01);
  const SE2 guess(0.25, 0.0, 0.0);  // odometry says 0.25 m along the corridor
  const ScanPair corridor = MakePair(CorridorWalls(), SE2(0, 0.1, 0.0), T_true, 0.01, 5);
  const IcpResult r = RegisterIcp(corridor.source.points, corridor.target, guess, ConfigFor(kVariants[3]));
  EXPECT_TRUE(r.degenerate);
  EXPECT_EQ(r.degenerate_dimensions, 1);
  EXPECT_GT(std::abs(r.degenerate_direction.x()), 0.99);  // the corridor's axis
  // Solution remapping: the axis component stays at the guess; the rest comes from ICP.
  EXPECT_NEAR(r.T_target_source.x, guess.x, 1e-3);
  EXPECT_NEAR(r.T_target_source.y, T_true.y, 3e-3);
  EXPECT_NEAR(r.T_target_source.theta, T_true.theta, 2e-3);
  EXPECT_GT(r.covariance(0, 0), 1e3 * r.covariance(1, 1));  // the axis is uncertain

  const ScanPair room = MakePair(RoomWalls(), SE2(0, 0.1, 0.0), T_true, 0.01, 5);
  const IcpResult q = RegisterIcp(room.source.points, room.target, guess, ConfigFor(kVariants[3]));
  EXPECT_FALSE(q.degenerate);
  EXPECT_NEAR(q.T_target_source.x, T_true.x, 3e-3);
}

TEST(Icp, RobustKernelsResistClutter) {
  // 25% of the source points are clutter near the walls (within the gate).
  const SE2 T_true(0.12, -0.06, 0.03);
  ScanPair pair = MakePair(RoomWalls(), SE2(), T_true, 0.005, 6);
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  const size_t n = pair.source.points.size();
  for (size_t i = 0; i < n / 4; ++i) pair.source.points[i * 4] += Eigen::Vector2d(u(rng), u(rng));
  IcpConfig c = ConfigFor(kVariants[2]);
  c.convergence_translation_m = 1e-5;
  c.convergence_rotation_rad = 1e-5;
  const SE2 odometry_guess(0.15, -0.04, 0.02);  // redescending kernels need a fair start
  const IcpResult plain = RegisterIcp(pair.source.points, pair.target, odometry_guess, c);
  c.robust_kernel = IcpRobustKernel::kGemanMcClure;
  c.robust_scale_m = 0.03;
  const IcpResult gm = RegisterIcp(pair.source.points, pair.target, odometry_guess, c);
  c.robust_kernel = IcpRobustKernel::kNone;
  c.trim_fraction = 0.3;
  const IcpResult trimmed = RegisterIcp(pair.source.points, pair.target, odometry_guess, c);
  const auto err = [&](const IcpResult& r) { return (r.T_target_source.translation() - T_true.translation()).norm(); };
  EXPECT_LT(err(gm), 0.004);
  EXPECT_LT(err(trimmed), 0.006);
  EXPECT_LE(err(gm), err(plain));
  std::printf("clutter error: plain %.4f gm %.4f trimmed %.4f m\n", err(plain), err(gm), err(trimmed));
}

TEST(Icp, RobustWeights) {
  EXPECT_DOUBLE_EQ(RobustWeight(IcpRobustKernel::kNone, 5.0, 0.1), 1.0);
  EXPECT_DOUBLE_EQ(RobustWeight(IcpRobustKernel::kHuber, 0.05, 0.1), 1.0);
  EXPECT_DOUBLE_EQ(RobustWeight(IcpRobustKernel::kHuber, -0.4, 0.1), 0.25);
  EXPECT_DOUBLE_EQ(RobustWeight(IcpRobustKernel::kGemanMcClure, 0.0, 0.1), 1.0);
  EXPECT_NEAR(RobustWeight(IcpRobustKernel::kGemanMcClure, 0.1, 0.1), 0.25, 1e-15);
}

TEST(Icp, TooFewPointsIsNotConverged) {
  const ScanPair pair = MakePair(RoomWalls(), SE2(), SE2(0.1, 0, 0), 0.0, 2);
  const std::vector<Eigen::Vector2d> few(pair.source.points.begin(), pair.source.points.begin() + 5);
  const IcpResult r = RegisterIcp(few, pair.target, SE2(), IcpConfig{});
  EXPECT_FALSE(r.converged);
}

}  // namespace
}  // namespace slambox
