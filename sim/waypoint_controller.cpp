#include "sim/waypoint_controller.hpp"

#include <algorithm>
#include <cmath>

namespace slambox {

WaypointController::WaypointController(std::vector<Eigen::Vector2d> path, int laps, const ControllerConfig& config)
    : path_(std::move(path)), laps_(path_.empty() ? 0 : std::max(laps, 0)), config_(config) {}

VelocityCommand WaypointController::Update(const SE2& pose, double dt_s) {
  const ControllerConfig& c = config_;
  VelocityCommand cmd;
  while (!done()) {
    const Eigen::Vector2d to_goal = target_position() - pose.translation();
    const double distance = to_goal.norm();
    if (distance <= c.reach_tolerance_m) {  // reached: next waypoint, turn to face it first
      ++target_;
      turning_ = true;
      continue;
    }
    const double error = NormalizeAngle(std::atan2(to_goal.y(), to_goal.x()) - pose.theta);
    if (!turning_ && std::abs(error) > c.realign_rad && distance > 0.1) turning_ = true;
    if (turning_ && std::abs(error) <= c.align_tolerance_rad) turning_ = false;
    if (turning_) {
      // Stop first, then turn with a rate that brakes to zero at the target heading
      // (w <= sqrt(2 alpha |error|)) and never overshoots within one step.
      cmd.v_mps = std::max(0.0, last_.v_mps - c.accel_mps2 * dt_s);
      if (cmd.v_mps == 0.0) {
        const double w = std::min({c.max_turn_rate_rps, std::sqrt(2.0 * c.turn_accel_rps2 * std::abs(error)),
                                   std::abs(error) / dt_s, std::abs(last_.w_rps) + c.turn_accel_rps2 * dt_s});
        cmd.w_rps = std::copysign(w, error);
      }
    } else {
      cmd.v_mps = std::min({c.max_speed_mps, last_.v_mps + c.accel_mps2 * dt_s,
                            std::sqrt(2.0 * c.accel_mps2 * distance), distance / dt_s});
      // Heading correction only while the goal bearing is well defined.
      const double w = distance > 0.1 ? c.heading_gain_per_s * error : 0.0;
      cmd.w_rps = std::clamp(w, -c.max_turn_rate_rps, c.max_turn_rate_rps);
    }
    break;
  }
  last_ = cmd;
  return cmd;
}

}  // namespace slambox
