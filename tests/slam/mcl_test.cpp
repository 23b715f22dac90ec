// mcl: the 1-D squared distance transform against brute force, the likelihood field
// against exact distances to the walls, tracking accuracy and consistency on the ring
// corridor (fixed seeds), recovery from a spread-out start, determinism, input errors.
#include "slam/mcl.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <limits>
#include <random>

#include "core/error.hpp"
#include "slam/dead_reckoning.hpp"
#include "slam/likelihood_field.hpp"
#include "slam/map_points.hpp"
#include "tests/slam/icp_module_support.hpp"

namespace slambox {
namespace {

TEST(LikelihoodField, OneDimensionalTransformMatchesBruteForce) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double inf = std::numeric_limits<double>::infinity();
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<double> f(1 + trial % 37);
    for (double& v : f) v = u(rng) < 0.7 ? inf : 20.0 * u(rng);
    std::vector<double> d = f;
    SquaredDistanceTransform1d(d);
    for (size_t q = 0; q < f.size(); ++q) {
      double best = inf;
      for (size_t p = 0; p < f.size(); ++p) best = std::min(best, (double(q) - double(p)) * (double(q) - double(p)) + f[p]);
      EXPECT_DOUBLE_EQ(d[q], best) << "trial " << trial << " q " << q;
    }
  }
}

double SegmentDistance(const Eigen::Vector2d& p, const Segment& s) {
  const Eigen::Vector2d ab = s.b - s.a;
  const double t = std::clamp((p - s.a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (s.a + t * ab - p).norm();
}

TEST(LikelihoodField, DistancesMatchTheWallsWithinACell) {
  const World w = testing::RingWorld();
  const double res = 0.05, clamp = 1.0;
  const DistanceGrid g = MakeDistanceGrid(SampleWorldOutlines(w, 0.01), res, clamp, clamp);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> x(-3.0, 13.0);
  double worst = 0.0;
  for (int i = 0; i < 20000; ++i) {
    const Eigen::Vector2d p(x(rng), x(rng));
    double truth = clamp;
    for (const Segment& s : w.wall_segments) truth = std::min(truth, SegmentDistance(p, s));
    worst = std::max(worst, std::abs(g.At(p) - truth));
  }
  // Bilinear interpolation of |d| rounds the V at a wall by at most ~half a cell.
  EXPECT_LT(worst, 0.6 * res);
  EXPECT_EQ(g.At(Eigen::Vector2d(1e3, 1e3)), clamp);  // outside the grid: the clamp
}

// Position RMSE [m] on ring seeds 41, 42 and the ANEES over both; the test prints them:
// ./build/tests/slam_mcl_test --gtest_filter=Mcl.TracksTheRing*
constexpr double kRingRmse_m[] = {0.01429, 0.01500};
constexpr double kRingAnees = 1.132;

TEST(Mcl, TracksTheRingAndItsCovarianceIsPlausible) {
  double anees = 0;
  for (int i = 0; i < 2; ++i) {
    const std::uint64_t seed = 41 + i;
    const Stream s = testing::RingStream(seed, 1);
    const Estimate e = testing::RunModule(MclModule(), s);
    const double mcl = testing::PositionRmse(e, s);
    const double odo = testing::PositionRmse(testing::RunModule(DeadReckoningModule(), s), s);
    const double a = testing::PoseAnees(e, s);
    std::printf("ring seed %d: odometry %.3f m, mcl %.5f m, ANEES %.3f\n", static_cast<int>(seed), odo, mcl, a);
    EXPECT_TRUE(testing::NoWorseThanMeasured(mcl, kRingRmse_m[i])) << "seed " << seed;
    EXPECT_LT(mcl, odo / 8);
    anees += a / 2;
  }
  std::printf("mcl ANEES over 2 runs %.3f\n", anees);
  EXPECT_TRUE(testing::AneesNearMeasured(anees, kRingAnees, testing::PoseAneesWindow(2)));
}

// Final position error [m] from the spread-out start (ring seed 43); the test prints it:
// ./build/tests/slam_mcl_test --gtest_filter=Mcl.ConvergesFromASpreadOutStart
constexpr double kSpreadStartEndError_m = 0.0069;

TEST(Mcl, ConvergesFromASpreadOutStart) {
  const Stream s = testing::RingStream(43, 1);
  const Estimate e = testing::RunModule(MclModule(), s, {{"init_sigma_xy_m", "0.3"}, {"init_sigma_theta_deg", "5"}});
  const SE2& first = e.trajectory.front().pose;
  EXPECT_GT(e.trajectory.front().covariance(0, 0), 0.05);  // the cloud starts wide ...
  const PoseEstimate& last = e.trajectory.back();
  const SE2& truth = s.groundtruth.back().pose;
  std::printf("start (%.3f, %.3f), end error %.5f m\n", first.x, first.y, (last.pose.translation() - truth.translation()).norm());
  EXPECT_TRUE(testing::NoWorseThanMeasured((last.pose.translation() - truth.translation()).norm(),
                                           kSpreadStartEndError_m));  // ... and locks on
  EXPECT_LT(last.covariance(0, 0), 0.01);
}

TEST(Mcl, OneScanWeighsTheCloudByTheLikelihoodField) {
  // A corridor between walls at y = -1 and y = +1, two beams straight up and down with range
  // 1, headings exact: a particle at lateral offset y sees both endpoints |y| from a wall, so
  // its weight is L(|y|)^2 with L(d) = z_hit N(d; 0, sigma_hit) + z_rand / range_max (Thrun
  // 6.4, the likelihood field). The cloud's weighted variance of y after the scan (recorded
  // before resampling) must match prior N(0, 0.2^2) times that weight, integrated here.
  StreamHeader h;
  h.world.wall_segments = {{Eigen::Vector2d(-20, -1), Eigen::Vector2d(20, -1)},
                           {Eigen::Vector2d(-20, 1), Eigen::Vector2d(20, 1)}};
  h.sensors.lidar = LidarConfig{};
  h.sensors.lidar->range_max_m = 30.0;
  h.seed = 3;
  MclConfig c;
  c.particles = 20000;
  c.init_sigma_xy_m = 0.2;
  c.init_sigma_theta_deg = 0.0;
  c.beam_step = 1;
  c.grid_resolution_m = 0.01;
  Mcl mcl(c);
  mcl.Start(h);
  LaserScanEvent scan;
  scan.t_s = 0.1;
  scan.angle_min_rad = -M_PI / 2;
  scan.angle_increment_rad = M_PI;
  scan.range_max_m = 30.0;
  scan.ranges_m = {1.0, 1.0};
  scan.valid = {1, 1};
  mcl.OnLaserScan(scan);
  const Estimate e = mcl.Finish();
  ASSERT_EQ(e.trajectory.size(), 2u);
  double num = 0.0, den = 0.0;
  const double norm = c.z_hit / (std::sqrt(2 * M_PI) * c.sigma_hit_m), z_rand = (1 - c.z_hit) / 30.0;
  for (double y = -1.0; y <= 1.0; y += 1e-4) {
    const double L = norm * std::exp(-0.5 * y * y / (c.sigma_hit_m * c.sigma_hit_m)) + z_rand;
    const double w = std::exp(-0.5 * y * y / (0.2 * 0.2)) * L * L;
    num += w * y * y, den += w;
  }
  const double expected = num / den;  // 0.0134 m^2; the prior's is 0.04
  const double var_y = e.trajectory.back().covariance(1, 1);
  std::printf("posterior var(y) %.5f m^2, expected %.5f m^2\n", var_y, expected);
  EXPECT_NEAR(var_y / expected, 1.0, 0.1);
  EXPECT_NEAR(e.trajectory.front().covariance(1, 1) / 0.04, 1.0, 0.05);  // the prior cloud
}

TEST(Mcl, DeterministicAndNeedsAMap) {
  Stream s = testing::RingStream(44, 1);
  const Estimate a = testing::RunModule(MclModule(), s, {{"particles", "100"}});
  const Estimate b = testing::RunModule(MclModule(), s, {{"particles", "100"}});
  ASSERT_EQ(a.trajectory.size(), b.trajectory.size());
  for (size_t i = 0; i < a.trajectory.size(); ++i) EXPECT_EQ(a.trajectory[i].pose.vector(), b.trajectory[i].pose.vector());
  EXPECT_THROW(testing::RunModule(MclModule(), s, {{"particles", "0"}}), InputError);
  EXPECT_THROW(testing::RunModule(MclModule(), s, {{"z_hit", "1.5"}}), InputError);
  s.header.world = World{};
  EXPECT_THROW(testing::RunModule(MclModule(), s), InputError);
}

}  // namespace
}  // namespace slambox
