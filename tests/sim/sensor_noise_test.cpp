// Sensor noise matches the configured standard deviations (confidence bounds, fixed seeds).
#include <gtest/gtest.h>

#include "core/odometry_model.hpp"
#include "noise_statistics.hpp"
#include "sim/gyro_sensor.hpp"
#include "sim/landmark_sensor.hpp"
#include "sim/lidar.hpp"
#include "sim/odometry_sensor.hpp"

namespace slambox {
namespace {

using testing::ExpectBinomial;
using testing::ExpectGaussian;

constexpr double kDeg = M_PI / 180.0;

/// A long wall at x = 5.
StaticGeometryIndex WallAtFive() {
  StaticGeometry g;
  g.segments.push_back({{5, -50}, {5, 50}});
  return StaticGeometryIndex(g);
}

TEST(LidarNoise, RangeNoiseHasConfiguredSigma) {
  const StaticGeometryIndex index = WallAtFive();
  LidarConfig cfg{.beams = 11, .fov_deg = 40, .sigma_range_m = 0.05};
  LidarSensor lidar(cfg, 11);
  std::vector<double> residuals;
  for (int k = 0; k < 500; ++k) {
    const LaserScanEvent scan = lidar.Scan(0.0, SE2(), RayScene{&index, {}});
    for (int i = 0; i < cfg.beams; ++i) {
      ASSERT_EQ(scan.valid[i], 1);
      residuals.push_back(scan.ranges_m[i] - 5.0 / std::cos(scan.angle_min_rad + i * scan.angle_increment_rad));
    }
  }
  ExpectGaussian(residuals, 0.0, 0.05, "lidar range");
}

TEST(LidarNoise, BearingNoiseJittersTheTrueRay) {
  const StaticGeometryIndex index = WallAtFive();
  // One beam at +45 deg (fov 90, 2 beams: -45 and +45), no range noise: the hit range
  // 5 / cos(45 deg + delta) reveals the jitter delta.
  LidarConfig cfg{.beams = 2, .fov_deg = 90, .sigma_range_m = 0.0, .sigma_bearing_deg = 0.5};
  LidarSensor lidar(cfg, 12);
  std::vector<double> jitter_deg;
  for (int k = 0; k < 3000; ++k) {
    const LaserScanEvent scan = lidar.Scan(0.0, SE2(), RayScene{&index, {}});
    EXPECT_DOUBLE_EQ(scan.angle_min_rad + scan.angle_increment_rad, M_PI / 4);  // nominal angle reported
    jitter_deg.push_back((std::acos(5.0 / scan.ranges_m[1]) - M_PI / 4) / kDeg);
  }
  ExpectGaussian(jitter_deg, 0.0, 0.5, "lidar bearing");
}

TEST(LidarNoise, DropoutsAreInvalidAtMaxRangeWithConfiguredRate) {
  const StaticGeometryIndex index = WallAtFive();
  LidarConfig cfg{.beams = 100, .fov_deg = 60, .range_max_m = 30, .dropout_prob = 0.2};
  LidarSensor lidar(cfg, 13);
  double dropped = 0.0;
  for (int k = 0; k < 100; ++k) {
    const LaserScanEvent scan = lidar.Scan(0.0, SE2(), RayScene{&index, {}});
    for (int i = 0; i < cfg.beams; ++i)
      if (!scan.valid[i]) {
        ++dropped;
        EXPECT_EQ(scan.ranges_m[i], 30.0);
      }
  }
  ExpectBinomial(dropped, 100.0 * 100.0, 0.2, "dropouts");
}

TEST(OdometryNoise, ThrunModelSigmas) {
  // Noise small enough that the sampled trans stays positive (7 sigma), so Decompose
  // recovers the sampled (rot1, trans, rot2) exactly.
  const std::array<double, 4> alpha = {0.02, 0.005, 0.02, 0.005};
  const SE2 truth(1.0, 0.3, 0.4);
  const OdometryIncrement u = Decompose(truth);
  const Eigen::Matrix3d M = IncrementCovariance(u, alpha);
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> r1, tr, r2;
  for (int k = 0; k < 20000; ++k) {
    const OdometryIncrement s = Decompose(SampleOdometry(truth, alpha, rng, normal));
    r1.push_back(NormalizeAngle(s.rot1 - u.rot1));
    tr.push_back(s.trans - u.trans);
    r2.push_back(NormalizeAngle(s.rot2 - u.rot2));
  }
  ExpectGaussian(r1, 0.0, std::sqrt(M(0, 0)), "rot1");
  ExpectGaussian(tr, 0.0, std::sqrt(M(1, 1)), "trans");
  ExpectGaussian(r2, 0.0, std::sqrt(M(2, 2)), "rot2");
}

TEST(OdometryNoise, NoiseFreeSensorReportsTheTrueDeltaAndIgnoresTeleports) {
  OdometrySensor odo(OdometryConfig{.alpha = {0, 0, 0, 0}}, 1, SE2(1, 2, 0.5));
  const SE2 a(1.5, 2.2, 0.7);
  const OdometryEvent e = odo.Measure(0.02, a);
  const SE2 expect = Between(SE2(1, 2, 0.5), a);
  EXPECT_NEAR(e.delta.x, expect.x, 1e-12);
  EXPECT_NEAR(e.delta.y, expect.y, 1e-12);
  EXPECT_NEAR(e.delta.theta, expect.theta, 1e-12);
  const SE2 b = a * SE2(0.01, 0, 0.02);  // small wheel motion, then a kidnap to far away
  const SE2 to(-7, 3, 2.0);
  odo.Teleport(b, to);
  const OdometryEvent f = odo.Measure(0.04, to * SE2(0.02, 0, 0));
  EXPECT_NEAR(f.delta.x, (Between(a, b) * SE2(0.02, 0, 0)).x, 1e-12);
  EXPECT_NEAR(f.delta.theta, 0.02, 1e-12);
}

TEST(GyroNoise, BiasAndSigmaInRadiansPerSecond) {
  GyroSensor gyro(GyroConfig{.rate_hz = 100, .sigma_dps = 0.5, .bias_dps = 2.0}, 3);
  std::vector<double> rates;
  for (int k = 0; k < 5000; ++k) rates.push_back(gyro.Measure(0.0, 0.3).yaw_rate_rps);
  ExpectGaussian(rates, 0.3 + 2.0 * kDeg, 0.5 * kDeg, "gyro");
}

TEST(LandmarkNoise, RangeAndBearingSigmas) {
  const std::vector<TrueLandmark> posts = {{7, {5, 2}, 0.1}};
  StaticGeometry g;
  g.circles.push_back({posts[0].position, 0.1});
  const StaticGeometryIndex index(g);
  LandmarkSensor sensor(LandmarkSensorConfig{.sigma_range_m = 0.05, .sigma_bearing_deg = 1.0}, 21);
  const SE2 pose(1, 1, 0.3);
  const double true_range = std::hypot(4.0, 1.0), true_bearing = std::atan2(1.0, 4.0) - 0.3;
  std::vector<double> dr, db;
  for (int k = 0; k < 4000; ++k) {
    const LandmarkEvent e = sensor.Detect(0.0, pose, posts, RayScene{&index, {}});
    ASSERT_EQ(e.observations.size(), 1u);
    EXPECT_EQ(e.observations[0].id, 7);
    dr.push_back(e.observations[0].range_m - true_range);
    db.push_back(NormalizeAngle(e.observations[0].bearing_rad - true_bearing) / kDeg);
  }
  ExpectGaussian(dr, 0.0, 0.05, "landmark range");
  ExpectGaussian(db, 0.0, 1.0, "landmark bearing");
}

}  // namespace
}  // namespace slambox
