#pragma once
// Runs a scenario in a Box2D world and records the sensor stream and ground truth.
#include <cstdint>

#include "core/stream.hpp"
#include "sim/scenario.hpp"

namespace slambox {

struct SimulationOptions {
  double dt_s = 0.01;  ///< fixed physics and controller step
  /// Hard stop when duration_s == 0 and the robot never finishes (stuck): [s]
  double max_duration_s = 3600.0;
};

/// What happened physically during a run (for tests and the CLI summary).
struct SimulationReport {
  int wall_contacts = 0;   ///< robot-wall/post touches begun (0 = the path was driven cleanly)
  int mover_contacts = 0;  ///< robot-mover touches begun
  double distance_m = 0.0; ///< true distance driven (a kidnap jump not counted)
  bool path_completed = false;
  long steps = 0;          ///< simulator steps after t = 0
};

/// Deterministic: the same scenario, seed and options give a bit-identical Stream.
/// Each noise source (odometry, lidar, landmarks, gyro) has its own generator seeded
/// from (seed, source). Throws InputError if the robot cannot follow its path.
Stream Simulate(const Scenario& scenario, std::uint64_t seed, const SimulationOptions& options = {},
                SimulationReport* report = nullptr);

}  // namespace slambox
