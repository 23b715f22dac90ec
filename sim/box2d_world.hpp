#pragma once
// The physical world in Box2D 2.4: walls and posts as static bodies, movers as kinematic
// bodies tracking their paths, the robot as a dynamic disc driven by setting its
// velocities (so walls stop it: it never passes through them). Box2D types stay inside
// box2d_world.cpp. Box2D computes in float; poses read back are widened to double.
#include <memory>
#include <vector>

#include "core/se2.hpp"
#include "core/world.hpp"
#include "sim/ray_caster.hpp"
#include "sim/scenario.hpp"

namespace slambox {

/// Where a mover is at time t_s: it walks its polyline at speed_mps from the first point;
/// loop = back and forth forever, otherwise it stays at the last point.
Eigen::Vector2d MoverPositionAt(const MoverSpec& mover, double t_s);

struct ContactCounts {
  int robot_wall = 0;   ///< touches between the robot and a wall or post begun
  int robot_mover = 0;  ///< touches between the robot and a mover begun
};

class PhysicsWorld {
 public:
  /// Static geometry from `world` (MakeWorld(scenario)), movers and robot from `scenario`.
  PhysicsWorld(const Scenario& scenario, const World& world);
  ~PhysicsWorld();
  PhysicsWorld(const PhysicsWorld&) = delete;
  PhysicsWorld& operator=(const PhysicsWorld&) = delete;

  /// Forward speed [m/s] along the heading and yaw rate [rad/s] for the next step.
  void SetRobotVelocity(double v_mps, double w_rps);
  /// Moves movers toward their positions at t_next_s and advances the world by dt_s.
  void Step(double dt_s, double t_next_s);
  SE2 RobotPose() const;
  double RobotYawRate() const;  ///< [rad/s] the body's angular velocity
  void TeleportRobot(const SE2& T_world_robot);
  std::vector<MoverShape> Movers() const;
  ContactCounts contacts() const;

  /// Reference cast through b2World::RayCast (float), robot ignored: range or kNoHit.
  double RayCastBox2D(const Eigen::Vector2d& origin, const Eigen::Vector2d& dir, double max_range_m) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace slambox
