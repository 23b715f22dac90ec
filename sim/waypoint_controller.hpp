#pragma once
// Turn-then-drive waypoint follower for a differential-drive robot: turn in place to face
// the next waypoint, then drive straight with a proportional heading correction, slowing
// down so that it stops on the waypoint (v <= sqrt(2 a d)). The list repeats `laps` times.
#include <Eigen/Core>
#include <vector>

#include "core/se2.hpp"

namespace slambox {

struct ControllerConfig {
  double max_speed_mps = 1.0;
  double max_turn_rate_rps = M_PI / 2;
  double accel_mps2 = 1.0;                 ///< [m/s^2] speed-up and braking limit
  double turn_accel_rps2 = 2.0 * M_PI;     ///< [rad/s^2] limit when starting/stopping a turn
  double reach_tolerance_m = 0.02;         ///< a waypoint is reached within this distance
  double align_tolerance_rad = 0.5 * M_PI / 180.0;  ///< turning ends within this heading error
  double realign_rad = 30.0 * M_PI / 180.0;         ///< while driving, turn again beyond this error
  double heading_gain_per_s = 2.0;         ///< [1/s] w = gain * heading error while driving
};

struct VelocityCommand {
  double v_mps = 0.0;
  double w_rps = 0.0;
};

class WaypointController {
 public:
  WaypointController(std::vector<Eigen::Vector2d> path, int laps, const ControllerConfig& config);
  /// The command for the next dt_s from the true pose; marks waypoints reached.
  VelocityCommand Update(const SE2& pose, double dt_s);
  bool done() const { return target_ >= total_targets(); }
  int total_targets() const { return static_cast<int>(path_.size()) * laps_; }
  /// Index of the current target in the overall sequence (lap * path.size() + waypoint).
  int target() const { return target_; }
  const Eigen::Vector2d& target_position() const { return path_[target_ % path_.size()]; }

 private:
  std::vector<Eigen::Vector2d> path_;
  int laps_ = 1;
  ControllerConfig config_;
  int target_ = 0;
  bool turning_ = true;
  VelocityCommand last_;
};

}  // namespace slambox
