#include "sim/waypoint_controller.hpp"

#include <gtest/gtest.h>

namespace slambox {
namespace {

/// Integrates the unicycle x' = v cos(theta), y' = v sin(theta), theta' = w exactly per step.
SE2 Integrate(const SE2& pose, const VelocityCommand& cmd, double dt) {
  return pose * SE2(cmd.v_mps * dt, 0.0, 0.0) * SE2(0.0, 0.0, cmd.w_rps * dt);
}

TEST(WaypointController, RespectsLimitsAndVisitsEveryWaypoint) {
  const std::vector<Eigen::Vector2d> path = {{0, 0}, {4, 0}, {4, 3}, {-2, 5}};
  ControllerConfig c;
  c.max_speed_mps = 0.8;
  c.max_turn_rate_rps = 1.0;
  WaypointController controller(path, 2, c);
  const double dt = 0.01;
  SE2 pose(0, 0, 2.0);
  double v_prev = 0.0, closest_to_waypoint_2 = 1e9;
  int steps = 0;
  while (!controller.done() && steps < 100000) {
    const VelocityCommand cmd = controller.Update(pose, dt);
    ASSERT_LE(cmd.v_mps, c.max_speed_mps + 1e-12);
    ASSERT_GE(cmd.v_mps, 0.0);
    ASSERT_LE(std::abs(cmd.w_rps), c.max_turn_rate_rps + 1e-12);
    ASSERT_LE(cmd.v_mps - v_prev, c.accel_mps2 * dt + 1e-12);  // acceleration limit
    if (cmd.v_mps > 0.0 && cmd.w_rps != 0.0) {  // driving: only a small heading correction
      ASSERT_LE(std::abs(cmd.w_rps), c.heading_gain_per_s * c.realign_rad + 1e-12);
    }
    v_prev = cmd.v_mps;
    pose = Integrate(pose, cmd, dt);
    if (controller.target() == 2) closest_to_waypoint_2 = std::min(closest_to_waypoint_2, (pose.translation() - path[2]).norm());
    ++steps;
  }
  ASSERT_TRUE(controller.done());
  EXPECT_LT((pose.translation() - path.back()).norm(), c.reach_tolerance_m + 1e-9);
  EXPECT_LT(closest_to_waypoint_2, c.reach_tolerance_m + 1e-9);
  // Ideal time: length / v_max plus turns; the controller may not be more than ~40% slower.
  double length = 0.0;
  for (int lap = 0; lap < 2; ++lap)
    for (size_t i = 1; i <= path.size(); ++i)
      if (lap == 1 || i < path.size()) length += (path[i % path.size()] - path[i - 1]).norm();
  EXPECT_LT(steps * dt, 1.4 * length / c.max_speed_mps + 7 * M_PI / c.max_turn_rate_rps);
}

TEST(WaypointController, TurnsInPlaceBeforeDriving) {
  WaypointController controller({{0, 0}, {0, 5}}, 1, ControllerConfig{});
  SE2 pose(0, 0, 0);  // facing +x, the goal is at +y
  const VelocityCommand first = controller.Update(pose, 0.01);
  EXPECT_EQ(first.v_mps, 0.0);
  EXPECT_GT(first.w_rps, 0.0);
  for (int k = 0; k < 1000 && pose.theta < M_PI / 2 - 0.01; ++k) {
    const VelocityCommand cmd = controller.Update(pose, 0.01);
    EXPECT_EQ(cmd.v_mps, 0.0);
    pose = Integrate(pose, cmd, 0.01);
  }
  EXPECT_NEAR(pose.theta, M_PI / 2, 0.02);
}

}  // namespace
}  // namespace slambox
