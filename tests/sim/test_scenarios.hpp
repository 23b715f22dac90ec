#pragma once
// Scenarios built in code for the simulator tests (no YAML involved).
#include "sim/scenario.hpp"

namespace slambox::testing {

/// A 10 m x 8 m room with a pillar, two posts and a 2-lap rectangular path around the pillar.
inline Scenario RoomScenario() {
  Scenario s;
  s.name = "room";
  s.source = "test:room";
  WallSpec room;
  room.kind = WallSpec::Kind::kPolygon;
  room.points = {{0, 0}, {10, 0}, {10, 8}, {0, 8}};
  WallSpec pillar;
  pillar.kind = WallSpec::Kind::kBox;
  pillar.center = {5, 4};
  pillar.size = {2, 1};
  s.walls = {room, pillar};
  s.landmarks = {{{2, 7.4}, 0.1, 0, 0}, {{8, 0.6}, 0.1, 1, 0}};
  s.robot.start = {1.5, 1.5, 0.0};
  s.robot.path = {{1.5, 1.5}, {8.5, 1.5}, {8.5, 6.5}, {1.5, 6.5}};
  s.robot.laps = 2;
  s.sensors.odometry = OdometryConfig{};
  s.sensors.lidar = LidarConfig{};
  s.sensors.landmarks = LandmarkSensorConfig{};
  s.sensors.gyro = GyroConfig{.rate_hz = 50.0};
  return s;
}

}  // namespace slambox::testing
