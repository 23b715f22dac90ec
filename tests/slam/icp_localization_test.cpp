// icp-localization: the map sampler's closed forms, accuracy and consistency on the ring
// corridor (fixed seeds), the degenerate corridor (the axis stays with odometry), a world
// without walls is an input error, determinism.
#include "slam/icp_localization.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include "core/error.hpp"
#include "slam/dead_reckoning.hpp"
#include "slam/map_points.hpp"
#include "tests/slam/icp_module_support.hpp"

namespace slambox {
namespace {

TEST(MapPoints, SamplesSegmentsAndCirclesEvenly) {
  World w;
  w.wall_segments.push_back({Eigen::Vector2d(1, 1), Eigen::Vector2d(2, 1)});
  w.wall_circles.push_back({Eigen::Vector2d(5, 5), 0.5});
  const std::vector<Eigen::Vector2d> p = SampleWorldOutlines(w, 0.25);
  const int circle = static_cast<int>(std::ceil(2 * M_PI * 0.5 / 0.25));  // 13
  ASSERT_EQ(p.size(), 5u + circle);
  for (int i = 0; i < 5; ++i) EXPECT_NEAR((p[i] - Eigen::Vector2d(1 + 0.25 * i, 1)).norm(), 0, 1e-15);
  for (size_t i = 5; i < p.size(); ++i) EXPECT_NEAR((p[i] - Eigen::Vector2d(5, 5)).norm(), 0.5, 1e-12);
  EXPECT_TRUE(SampleWorldOutlines(World{}, 0.1).empty());
}

// Position RMSE [m] on ring seeds 31, 32 and the ANEES over both; the test prints them:
// ./build/tests/slam_icp_localization_test --gtest_filter=IcpLocalization.TracksTheRing*
constexpr double kRingRmse_m[] = {0.00616, 0.00590};
constexpr double kRingAnees = 1.103;

TEST(IcpLocalization, TracksTheRingFarBetterThanOdometryAndIsConsistent) {
  double anees = 0;
  for (int i = 0; i < 2; ++i) {
    const std::uint64_t seed = 31 + i;
    const Stream s = testing::RingStream(seed, 1);
    const Estimate e = testing::RunModule(IcpLocalizationModule(), s);
    const double loc = testing::PositionRmse(e, s);
    const double odo = testing::PositionRmse(testing::RunModule(DeadReckoningModule(), s), s);
    const double a = testing::PoseAnees(e, s);
    std::printf("ring seed %d: odometry %.3f m, icp-localization %.5f m, ANEES %.3f\n", static_cast<int>(seed), odo, loc, a);
    EXPECT_TRUE(testing::NoWorseThanMeasured(loc, kRingRmse_m[i])) << "seed " << seed;
    EXPECT_LT(loc, odo / 20);
    anees += a / 2;
  }
  std::printf("icp-localization ANEES over 2 runs %.3f\n", anees);
  EXPECT_TRUE(testing::AneesNearMeasured(anees, kRingAnees, testing::PoseAneesWindow(2)));
}

// Position RMSE [m] in the corridor (seed 5); the test prints it:
// ./build/tests/slam_icp_localization_test --gtest_filter=IcpLocalization.CorridorAxis*
constexpr double kCorridorRmse_m = 0.1202;

TEST(IcpLocalization, CorridorAxisStaysWithOdometry) {
  // Two parallel walls: ICP fixes the lateral position and heading, never the axis.
  World corridor;
  corridor.wall_segments = {{Eigen::Vector2d(-5, -1.5), Eigen::Vector2d(40, -1.5)},
                            {Eigen::Vector2d(-5, 1.5), Eigen::Vector2d(40, 1.5)}};
  testing::SyntheticOptions o;
  o.path = {{0, 0}, {30, 0}};
  o.seed = 5;
  o.sensors.odometry = OdometryConfig{};
  LidarConfig lidar;
  lidar.beams = 360;
  lidar.range_max_m = 10;  // the corridor's ends stay out of range
  o.sensors.lidar = lidar;
  const Stream s = testing::MakeSyntheticStream(o, corridor);
  const Estimate e = testing::RunModule(IcpLocalizationModule(), s);
  size_t far = 0;  // the pose at the far end of the corridor
  for (size_t i = 0; i < e.trajectory.size(); ++i)
    if (e.trajectory[i].pose.x > e.trajectory[far].pose.x) far = i;
  const Eigen::Matrix3d& P = e.trajectory[far].covariance;
  std::printf("far end: sigma_x %.3f m, sigma_y %.4f m\n", std::sqrt(P(0, 0)), std::sqrt(P(1, 1)));
  EXPECT_GT(P(0, 0), 25 * P(1, 1));  // along the axis: odometry's growing uncertainty
  double degenerate = 0;
  for (const auto& [t, v] : e.diagnostics.at("degenerate")) degenerate += v;
  EXPECT_GT(degenerate, 0.8 * e.diagnostics.at("degenerate").size());
  std::printf("corridor: icp-localization %.4f m\n", testing::PositionRmse(e, s));
  EXPECT_TRUE(testing::NoWorseThanMeasured(testing::PositionRmse(e, s), kCorridorRmse_m));
}

// A 4 m wide corridor ring around a 50 x 26 m block without features: along each leg ICP
// sees only the side walls, so the odometry's error along the axis (alpha 0.2: sigma ~0.5 m
// per leg) builds up unseen and shows across the next leg, beyond the 0.3 m pair gate. The
// tracker must take that correction at the corner (its prediction's 3 sigma widens the gate
// and the accepted correction) instead of pairing the wrong wall points and turning away.
// Position RMSE on stream seeds 1..10, before: 0.41 0.22 0.37 0.19 8.46 1.81 37.5 8.03 0.20
// 26.1 m (lost at a corner on 5, 6, 7, 8, 10); now 0.46 0.25 0.37 0.19 0.64 0.33 0.37 0.36 0.20
// 0.40 m (most of it the along-axis error each leg keeps until its corner); with the wide
// pass's kernel as wide as its gate (the test below) seeds 5..8 give 0.27 0.25 0.30 0.11 m.
// Seeds 5..8 run.
TEST(IcpLocalization, TakesTheCorrectionAnUnseenAxisErrorNeedsAtTheNextCorner) {
  LidarConfig lidar;
  lidar.beams = 541;
  lidar.fov_deg = 180;
  lidar.sigma_range_m = 0.01;
  lidar.range_max_m = 8;
  for (std::uint64_t seed : {5, 6, 7, 8}) {
    const Stream s = testing::RectangleCorridorStream(2.0, seed, {0.05, 0.002, 0.2, 0.002}, lidar);
    const double rmse = testing::PositionRmse(testing::RunModule(IcpLocalizationModule(), s), s);
    std::printf("4 m corridor ring, seed %d: icp-localization %.3f m\n", static_cast<int>(seed), rmse);
    EXPECT_LT(rmse, 1.0) << "seed " << seed;
  }
}

// A 6 m corridor ring seen by a 180 deg, 8 m LIDAR with 3 cm noise. Near a corner the leg's
// end wall shows the along-axis error (0.5 m and more) the side walls could not. The wide
// first ICP pass pairs those points, but under the fine pass's robust kernel (Geman-McClure,
// 5 cm) a 0.5 m residual weighs ~1e-4: the end wall had no say, the axis stayed degenerate
// and the error met the next leg as a wrong turn (random world lidar3_6: lost, 17.7 m). The
// wide pass's kernel now has the width of its gate. Position RMSE on stream seeds 1..10,
// before: 0.31 0.47 0.17 0.13 0.17 0.22 0.11 0.17 0.48 0.47 m; now 0.18 0.23 0.16 0.13 0.15
// 0.19 0.11 0.13 0.21 0.25 m. Seeds 1, 2, 9, 10 run.
TEST(IcpLocalization, LetsTheWidePassSeeTheEndWall) {
  LidarConfig lidar;
  lidar.beams = 361;
  lidar.fov_deg = 180;
  lidar.sigma_range_m = 0.03;
  lidar.range_max_m = 8;
  for (std::uint64_t seed : {1, 2, 9, 10}) {
    const Stream s = testing::RectangleCorridorStream(3.0, seed, {0.1, 0.005, 0.1, 0.005}, lidar);
    const double rmse = testing::PositionRmse(testing::RunModule(IcpLocalizationModule(), s), s);
    std::printf("6 m corridor ring, seed %d: icp-localization %.3f m\n", static_cast<int>(seed), rmse);
    EXPECT_LT(rmse, 0.3) << "seed " << seed;
  }
}

TEST(IcpLocalization, NeedsAMapAndIsDeterministic) {
  Stream s = testing::RingStream(33, 1);
  const Estimate a = testing::RunModule(IcpLocalizationModule(), s);
  const Estimate b = testing::RunModule(IcpLocalizationModule(), s);
  ASSERT_EQ(a.trajectory.size(), b.trajectory.size());
  for (size_t i = 0; i < a.trajectory.size(); ++i) EXPECT_EQ(a.trajectory[i].pose.vector(), b.trajectory[i].pose.vector());
  s.header.world = World{};
  EXPECT_THROW(testing::RunModule(IcpLocalizationModule(), s), InputError);
  EXPECT_THROW(testing::RunModule(IcpLocalizationModule(), s, {{"map_spacing_m", "0"}}), InputError);
}

}  // namespace
}  // namespace slambox
