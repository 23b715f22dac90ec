#pragma once
// Simulated 2D LIDAR: one exact ray per beam (sim/ray_caster.hpp), Gaussian range noise,
// bearing jitter of the true ray (the scan reports nominal angles) and dropouts. Misses,
// dropouts and hits closer than range_min_m are reported invalid at range_max_m.
#include <cstdint>
#include <random>
#include <vector>

#include "core/sensors.hpp"
#include "core/stream.hpp"
#include "sim/ray_caster.hpp"

namespace slambox {

/// Beam angles in the robot frame: a full circle (fov >= 360) is split into `beams`
/// equal steps from -pi; a narrower fan puts its first and last beam on the fov's edges.
struct ScanAngles {
  double angle_min_rad = 0.0;
  double angle_increment_rad = 0.0;
};
ScanAngles LidarScanAngles(const LidarConfig& config);

class LidarSensor {
 public:
  LidarSensor(const LidarConfig& config, std::uint64_t seed);
  LaserScanEvent Scan(double t_s, const SE2& T_world_robot, const RayScene& scene);

 private:
  LidarConfig config_;
  ScanAngles angles_;
  std::vector<Eigen::Vector2d> beam_dirs_;  ///< unit beam directions in the robot frame
  // Per scan, reused: the beams' world directions and their static ranges (CastFan).
  std::vector<Eigen::Vector2d> world_dirs_;
  std::vector<double> static_ranges_;
  FanScratch fan_scratch_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  std::uniform_real_distribution<double> uniform_{0.0, 1.0};
};

}  // namespace slambox
