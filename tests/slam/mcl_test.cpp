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
