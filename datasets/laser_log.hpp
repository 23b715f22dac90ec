#pragma once
// A LaserLog (core/laser_log.hpp: what a CARMEN or MRPT rawlog reader found) -> Stream,
// the same way for every format. The stream's robot frame is the laser's frame, so scans
// need no mounting offset: odometry events are the increments between consecutive
// odometry poses (in time order), expressed in the laser frame, so at each scan the
// integrated odometry equals that scan's odometry pose; landmark observations are moved
// to the laser frame too. Times are seconds since the first message, rounded to `dt_s`;
// the header's time_origin_s is that first message's time, so log time = t_s +
// time_origin_s within dt_s / 2. Real logs have no ground truth.
#include <array>
#include <string>

#include "core/laser_log.hpp"
#include "core/stream.hpp"

namespace slambox {

struct LaserLogOptions {
  /// [m] returns beyond this are misses (at it too when the log has no validity flags,
  /// as CARMEN writes the maximum for "no return"); 0 = the log's (LaserLog::Scan::range_max_m
  /// of the first scan, or `log_range_max_m`), else 80 m.
  double range_max_m = 0.0;
  double range_min_m = 0.01;    ///< [m] shorter returns are invalid
  double sigma_range_m = 0.01;  ///< [m] written into the header's lidar block (logs do not say)
  /// Thrun's odometry noise (rot1, trans, rot2 model): a prior, logs do not say.
  std::array<double, 4> odometry_alpha = {0.05, 0.005, 0.05, 0.005};
  double dt_s = 0.001;  ///< [s] time step: every event time is a multiple of it
};

/// Throws InputError naming `name` for a log without scans, landmarks or odometry.
/// `log_range_max_m` (0 = none) is a range limit the log states elsewhere (CARMEN's PARAM).
Stream AssembleLaserLog(LaserLog log, const std::string& name, const LaserLogOptions& options,
                        double log_range_max_m = 0.0);

}  // namespace slambox
