#pragma once
// Shared by the scenario tests: a temporary directory for YAML files and a comparison of
// two Scenarios that ignores where they came from (source, line numbers).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "sim/scenario.hpp"

namespace slambox::testing {

/// A fresh directory under the system temp dir, removed at exit of the test.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("slambox_scenario_" + std::to_string(::getpid()) + "_" + (info ? info->name() : "x"));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  std::string Write(const std::string& name, const std::string& text) const {
    const std::filesystem::path file = path_ / name;
    std::ofstream(file, std::ios::binary) << text;
    return file.string();
  }

 private:
  std::filesystem::path path_;
};

inline void ExpectSameScenario(const Scenario& a, const Scenario& b) {
  EXPECT_EQ(a.version, b.version);
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.description, b.description);
  EXPECT_EQ(a.duration_s, b.duration_s);
  ASSERT_EQ(a.walls.size(), b.walls.size());
  for (std::size_t i = 0; i < a.walls.size(); ++i) {
    const WallSpec &x = a.walls[i], &y = b.walls[i];
    EXPECT_TRUE(x.kind == y.kind && x.points == y.points && x.center == y.center && x.size == y.size &&
                x.angle_deg == y.angle_deg && x.radius_m == y.radius_m)
        << "wall " << i;
  }
  ASSERT_EQ(a.landmarks.size(), b.landmarks.size());
  for (std::size_t i = 0; i < a.landmarks.size(); ++i)
    EXPECT_TRUE(a.landmarks[i].pos == b.landmarks[i].pos && a.landmarks[i].radius_m == b.landmarks[i].radius_m &&
                a.landmarks[i].id == b.landmarks[i].id)
        << "landmark " << i;
  ASSERT_EQ(a.movers.size(), b.movers.size());
  for (std::size_t i = 0; i < a.movers.size(); ++i) {
    const MoverSpec &x = a.movers[i], &y = b.movers[i];
    EXPECT_TRUE(x.is_box == y.is_box && x.radius_m == y.radius_m && x.size == y.size && x.path == y.path &&
                x.speed_mps == y.speed_mps && x.loop == y.loop)
        << "mover " << i;
  }
  const RobotSpec &r = a.robot, &q = b.robot;
  EXPECT_TRUE(r.start.x == q.start.x && r.start.y == q.start.y && r.start.theta_deg == q.start.theta_deg);
  EXPECT_TRUE(r.radius_m == q.radius_m && r.max_speed_mps == q.max_speed_mps &&
              r.max_turn_rate_deg_s == q.max_turn_rate_deg_s && r.path == q.path && r.laps == q.laps);
  ASSERT_EQ(r.kidnap.has_value(), q.kidnap.has_value());
  if (r.kidnap) {
    EXPECT_TRUE(r.kidnap->at_s == q.kidnap->at_s && r.kidnap->to.x == q.kidnap->to.x &&
                r.kidnap->to.y == q.kidnap->to.y && r.kidnap->to.theta_deg == q.kidnap->to.theta_deg);
  }
  const SensorSuite &s = a.sensors, &t = b.sensors;
  ASSERT_EQ(s.odometry.has_value(), t.odometry.has_value());
  if (s.odometry) {
    EXPECT_TRUE(s.odometry->rate_hz == t.odometry->rate_hz && s.odometry->alpha == t.odometry->alpha);
  }
  ASSERT_EQ(s.lidar.has_value(), t.lidar.has_value());
  if (s.lidar) {
    const LidarConfig &l = *s.lidar, &m = *t.lidar;
    EXPECT_TRUE(l.rate_hz == m.rate_hz && l.beams == m.beams && l.fov_deg == m.fov_deg &&
                l.range_min_m == m.range_min_m && l.range_max_m == m.range_max_m && l.sigma_range_m == m.sigma_range_m &&
                l.sigma_bearing_deg == m.sigma_bearing_deg && l.dropout_prob == m.dropout_prob);
  }
  ASSERT_EQ(s.landmarks.has_value(), t.landmarks.has_value());
  if (s.landmarks) {
    const LandmarkSensorConfig &l = *s.landmarks, &m = *t.landmarks;
    EXPECT_TRUE(l.rate_hz == m.rate_hz && l.range_max_m == m.range_max_m && l.fov_deg == m.fov_deg &&
                l.sigma_range_m == m.sigma_range_m && l.sigma_bearing_deg == m.sigma_bearing_deg &&
                l.known_ids == m.known_ids && l.detection_prob == m.detection_prob &&
                l.detection_prob_known == m.detection_prob_known && l.clutter_per_scan == m.clutter_per_scan);
  }
  ASSERT_EQ(s.gyro.has_value(), t.gyro.has_value());
  if (s.gyro) {
    EXPECT_TRUE(s.gyro->rate_hz == t.gyro->rate_hz && s.gyro->sigma_dps == t.gyro->sigma_dps &&
                s.gyro->bias_dps == t.gyro->bias_dps);
  }
}

}  // namespace slambox::testing
