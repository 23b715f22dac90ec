#pragma once
// A real log as its reader found it, before it becomes a Stream (datasets/laser_log.hpp
// assembles it the one way for every format): poses and times in the log's own clock
// and odometry frame. Plain data, so a format reader living in a plugin (the MRPT rawlog
// reader in slambox-mrpt.so) hands it over without its library's types.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/se2.hpp"
#include "core/sensors.hpp"
#include "core/stream.hpp"

namespace slambox {

struct LaserLog {
  struct Odometry {
    double ts = 0.0;  ///< [s] the log's clock
    SE2 pose;         ///< robot in the odometry frame
  };
  struct Scan {
    double ts = 0.0;
    double angle_min_rad = 0.0;  ///< beam 0, in the laser frame, increasing angles
    double angle_increment_rad = 0.0;
    double range_max_m = 0.0;      ///< the sensor's, 0 = unknown (the assembly's default applies)
    std::vector<double> ranges_m;
    std::vector<std::uint8_t> valid;  ///< empty: decided by range alone
  };
  struct Landmarks {
    double ts = 0.0;
    std::vector<LandmarkObservation> observations;  ///< range and bearing from the robot origin
  };
  std::string format;  ///< "CARMEN log", "MRPT rawlog": the header's comment says where it came from
  std::vector<Odometry> odometry;  ///< file order (the assembly sorts by time, stably)
  std::vector<Scan> scans;
  std::vector<Landmarks> landmarks;
  SE2 T_robot_laser;  ///< the laser's mounting: the stream's robot frame is the laser's
  std::optional<LandmarkSensorConfig> landmark_sensor;  ///< when the log has landmark observations
};

/// How a rawlog is laid out (MRPT supports both): kObservations, a flat list of observations
/// (odometry poses among them: RawLogViewer, rawlog-edit, icp-slam); kFrames, pairs of an
/// action (the odometry increment) and a sensory frame (what MRPT's kf-slam and rbpf-slam apps
/// read: they skip a flat list).
enum class RawlogLayout { kObservations, kFrames };

/// The entry point of a plugin that reads and writes a log format (the MRPT plugin's
/// rawlog): `extern "C" const LogFormatEntry* slambox_rawlog_format()`. read() throws
/// InputError naming the file; write() writes atomically and throws on failure.
struct LogFormatEntry {
  int api_version;  ///< SLAMBOX_API_VERSION the plugin was built with
  LaserLog (*read)(const std::string& path);
  void (*write)(const Stream& stream, const std::string& path, RawlogLayout layout);
};

}  // namespace slambox

#define SLAMBOX_RAWLOG_FORMAT_SYMBOL "slambox_rawlog_format"
