#pragma once
// The Stream: the seam between simulation (or a real log) and SLAM modules. A scenario
// and a seed are simulated once; every module replays the identical stream.
// Times are seconds since the start of the run; every event time is exactly a
// multiple of the simulator's step (computed as step_index * dt_s), so estimates and
// ground truth share timestamps bit for bit.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "core/se2.hpp"
#include "core/sensors.hpp"
#include "core/world.hpp"

namespace slambox {

/// Wheel odometry: the measured motion since the previous odometry event, as the pose of
/// the robot now in the robot frame at the previous event (x̄_{t-1}^-1 x̄_t, Thrun 5.4).
struct OdometryEvent {
  double t_s = 0.0;
  SE2 delta;
};

/// One LIDAR sweep. Beam i points at angle_min_rad + i * angle_increment_rad in the robot
/// frame. A miss (nothing within range_max_m) or a dropout has valid[i] == 0 and
/// ranges_m[i] == range_max_m; it is never a fake hit.
struct LaserScanEvent {
  double t_s = 0.0;
  double angle_min_rad = 0.0;
  double angle_increment_rad = 0.0;
  double range_min_m = 0.0;
  double range_max_m = 0.0;
  std::vector<double> ranges_m;
  std::vector<std::uint8_t> valid;
};

struct LandmarkObservation {
  double range_m = 0.0;
  double bearing_rad = 0.0;  ///< in the robot frame, in [-pi, pi)
  int id = -1;               ///< landmark id when the detector knows ids; -1 otherwise (and for clutter)
};

struct LandmarkEvent {
  double t_s = 0.0;
  std::vector<LandmarkObservation> observations;
};

struct GyroEvent {
  double t_s = 0.0;
  double yaw_rate_rps = 0.0;  ///< [rad/s], with noise and bias
};

using SensorEvent = std::variant<OdometryEvent, LaserScanEvent, LandmarkEvent, GyroEvent>;

inline double EventTime(const SensorEvent& e) {
  return std::visit([](const auto& ev) { return ev.t_s; }, e);
}

struct StampedPose {
  double t_s = 0.0;
  SE2 pose;  ///< T_world_robot
};

struct StreamHeader {
  /// 2: CRC-32 checksum (1, FNV-1a 64, is still read). core/stream_io.hpp has the layout.
  static constexpr int kFormatVersion = 2;
  int format_version = kFormatVersion;
  std::string slambox_version;
  std::string scenario_name;
  std::string scenario_yaml;  ///< the resolved scenario, every default filled in
  std::uint64_t seed = 0;
  double dt_s = 0.01;         ///< simulator step; ground truth is sampled at every step
  double duration_s = 0.0;
  SE2 start_pose;             ///< modules start here (DESIGN: estimates start at the true start)
  /// [s] a converted log's own clock at stream time 0 (log time = t_s + time_origin_s), so
  /// times from the log's tools (e.g. relation files) map onto the stream; absent when
  /// the stream was simulated or converted before the origin was recorded.
  std::optional<double> time_origin_s;
  SensorSuite sensors;
  World world;                ///< ground truth map; SLAM modules must not read it (localization may)
};

/// A converted log's scenario_yaml starts with this comment (a simulated stream's holds its
/// resolved scenario): a log has no seed and no scenario to re-simulate.
inline constexpr std::string_view kConvertedLogYamlPrefix = "# converted from ";
inline bool IsConvertedLog(const StreamHeader& h) { return h.scenario_yaml.starts_with(kConvertedLogYamlPrefix); }

struct Stream {
  StreamHeader header;
  std::vector<SensorEvent> events;       ///< time-ordered; ties keep simulator order
  std::vector<StampedPose> groundtruth;  ///< the true pose at every simulator step
};

}  // namespace slambox
