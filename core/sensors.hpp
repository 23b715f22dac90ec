#pragma once
// Sensor configurations as written in the scenario file (DESIGN.md, `sensors:`). Angles
// are in degrees here because these structs mirror the file; code converts at use.
// All noise values are standard deviations. A sensor that is absent is std::nullopt.
#include <array>
#include <optional>

namespace slambox {

struct OdometryConfig {
  double rate_hz = 50.0;
  /// Thrun's odometry motion model (Prob. Robotics, Table 5.6): variances
  /// rot1: a1*rot1^2 + a2*trans^2, trans: a3*trans^2 + a4*(rot1^2 + rot2^2),
  /// rot2: a1*rot2^2 + a2*trans^2 (angles in rad, trans in m).
  std::array<double, 4> alpha = {0.05, 0.005, 0.05, 0.005};
};

struct LidarConfig {
  double rate_hz = 10.0;
  int beams = 360;
  double fov_deg = 360.0;        ///< centred on the robot's heading
  double range_min_m = 0.1;
  double range_max_m = 30.0;
  double sigma_range_m = 0.01;
  double sigma_bearing_deg = 0.0;  ///< the true ray direction jitters; the scan reports nominal angles
  double dropout_prob = 0.0;       ///< a dropped beam is reported invalid
};

struct LandmarkSensorConfig {
  double rate_hz = 10.0;
  double range_max_m = 15.0;
  double fov_deg = 360.0;
  double sigma_range_m = 0.05;
  double sigma_bearing_deg = 1.0;
  bool known_ids = true;
  double detection_prob = 1.0;
  /// false: the source does not say its P_D (a converted log); detection_prob is then only
  /// a placeholder, and modules that can measure the rate from the data do so.
  bool detection_prob_known = true;
  double clutter_per_scan = 0.0;  ///< Poisson mean of false detections per scan
};

struct GyroConfig {
  double rate_hz = 0.0;  ///< 0 = off
  double sigma_dps = 0.1;
  double bias_dps = 0.0;
};

struct SensorSuite {
  std::optional<OdometryConfig> odometry;
  std::optional<LidarConfig> lidar;
  std::optional<LandmarkSensorConfig> landmarks;
  std::optional<GyroConfig> gyro;
};

}  // namespace slambox
