#pragma once
// CARMEN laser logs (.clf / .log, optionally .gz / .bz2) -> Stream, so every module can
// replay a real run. Read messages (one per line, the ipc timestamp third from the end):
//   ODOM x y theta tv rv accel  ts host logger_ts
//   FLASER n r_1..r_n  x y theta  odom_x odom_y odom_theta  ts host logger_ts
//   ROBOTLASER1 type start_angle fov resolution max_range accuracy remission_mode
//               n r_1..r_n  m rem_1..rem_m  laser_x laser_y laser_theta
//               robot_x robot_y robot_theta  tv rv fwd_safety side_safety turn_axis  ts host logger_ts
//   PARAM robot_front_laser_max V ... / PARAM robot_frontlaser_offset V ...
// Other messages (RLASER, TRUEPOS, SYNC, NEFF, comments) are skipped.
//
// The stream's robot frame is the laser's frame, so scans need no mounting offset: the
// laser pose in the odometry frame is the odometry pose times the fixed offset, taken
// from the first scan's (laser pose, odometry pose) pair. Odometry events are the
// increments between consecutive odometry poses (ODOM messages and the odometry pose of
// every scan, in time order), so at each scan the integrated odometry equals that scan's
// odometry pose. Times are seconds since the first message, rounded to `dt_s`; the header's
// time_origin_s is that first message's ipc timestamp, so log time = t_s + time_origin_s
// within dt_s / 2 (relation files and other tools use the log's clock). The log
// has no ground truth: the stream's ground truth is empty and so are pose metrics.
#include <array>
#include <string>

#include "core/params.hpp"
#include "core/stream.hpp"

namespace slambox {

/// What to do with a message stamped earlier than the log's clock has already reached, by
/// more than kCarmenOutOfOrderToleranceS: stop with its line (the default), or skip it.
/// Logs written by a SLAM tool (the public intel-, freiburg-079- and csail-corrected logs)
/// stamp the corrected pose they write after each scan 0; sorted by time, those poses
/// would all land at the start and corrupt the odometry.
enum class CarmenOutOfOrder { kError, kDrop };
/// error, drop (for `convert carmen --out-of-order`).
const EnumNames<CarmenOutOfOrder>& CarmenOutOfOrderNames();
/// [s] Out-of-order messages within this of the clock so far are kept (sorted by time):
/// interleaved processes do that; the public logs' worst is 0.90 s (intel), 0.50 s (fr079).
inline constexpr double kCarmenOutOfOrderToleranceS = 5.0;

struct CarmenImportOptions {
  /// FLASER lines carry no beam geometry: the n beams span this field of view, centred
  /// ahead; n odd: the ends are at +-fov/2 (SICK 181 / 361), n even: step fov/n from -fov/2.
  double fov_deg = 180.0;
  /// [m] returns at or beyond this are misses (CARMEN writes the maximum for "no return");
  /// 0 = the log's PARAM robot_front_laser_max, else ROBOTLASER1's max_range, else 80 m.
  double range_max_m = 0.0;
  double range_min_m = 0.01;    ///< [m] shorter returns are invalid
  double sigma_range_m = 0.01;  ///< [m] written into the header's lidar block (the log does not say)
  /// Thrun's odometry noise (rot1, trans, rot2 model) for modules that propagate covariance;
  /// the log does not say, so this is a prior the user may set.
  std::array<double, 4> odometry_alpha = {0.05, 0.005, 0.05, 0.005};
  double dt_s = 0.001;  ///< [s] time step: every event time is a multiple of it
  CarmenOutOfOrder out_of_order = CarmenOutOfOrder::kError;
};

/// What the import skipped (for the converter's report).
struct CarmenImportReport {
  int out_of_order_dropped = 0;  ///< messages skipped by CarmenOutOfOrder::kDrop
};

/// Parses a whole log already in memory; `name` is the file name used in errors.
/// Throws InputError for a malformed line, a message out of order (kError), or a clock too
/// coarse to order the scans (more than half of consecutive scans share one timestamp).
Stream ParseCarmenLog(const std::string& text, const std::string& name, const CarmenImportOptions& options = {},
                      CarmenImportReport* report = nullptr);
/// Reads (and decompresses) the file, then parses it.
Stream ReadCarmenLog(const std::string& path, const CarmenImportOptions& options = {},
                     CarmenImportReport* report = nullptr);

}  // namespace slambox
