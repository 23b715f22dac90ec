#include "sim/lidar.hpp"

#include <algorithm>
#include <cmath>

#include "sim/seeding.hpp"

namespace slambox {

ScanAngles LidarScanAngles(const LidarConfig& c) {
  const double fov_rad = c.fov_deg * M_PI / 180.0;
  if (c.fov_deg >= 360.0) return {-M_PI, 2.0 * M_PI / c.beams};
  if (c.beams < 2) return {0.0, 0.0};
  return {-fov_rad / 2.0, fov_rad / (c.beams - 1)};
}

LidarSensor::LidarSensor(const LidarConfig& config, std::uint64_t seed)
    : config_(config), angles_(LidarScanAngles(config)), rng_(MakeGenerator(seed, NoiseSource::kLidar)) {
  for (int i = 0; i < config.beams; ++i) {
    const double a = angles_.angle_min_rad + i * angles_.angle_increment_rad;
    beam_dirs_.emplace_back(std::cos(a), std::sin(a));
  }
}

LaserScanEvent LidarSensor::Scan(double t_s, const SE2& T_world_robot, const RayScene& scene) {
  const LidarConfig& c = config_;
  LaserScanEvent scan;
  scan.t_s = t_s;
  scan.angle_min_rad = angles_.angle_min_rad;
  scan.angle_increment_rad = angles_.angle_increment_rad;
  scan.range_min_m = c.range_min_m;
  scan.range_max_m = c.range_max_m;
  scan.ranges_m.assign(c.beams, c.range_max_m);
  scan.valid.assign(c.beams, 0);
  const Eigen::Vector2d origin = T_world_robot.translation();
  const double sigma_bearing_rad = c.sigma_bearing_deg * M_PI / 180.0;
  const Eigen::Matrix2d R_world_robot = T_world_robot.rotation();
  // Without bearing jitter the beams are a regular fan: their static ranges come from one
  // CastFan (the same numbers as a Cast per beam); the random draws below are unchanged.
  const bool fan = sigma_bearing_rad == 0.0 && scene.statics != nullptr && angles_.angle_increment_rad > 0.0;
  if (fan) {
    world_dirs_.resize(beam_dirs_.size());
    for (size_t i = 0; i < beam_dirs_.size(); ++i) world_dirs_[i] = R_world_robot * beam_dirs_[i];
    scene.statics->CastFan(origin, T_world_robot.theta + angles_.angle_min_rad, angles_.angle_increment_rad,
                           world_dirs_, c.range_max_m, fan_scratch_, static_ranges_);
  }
  for (int i = 0; i < c.beams; ++i) {
    if (c.dropout_prob > 0.0 && uniform_(rng_) < c.dropout_prob) continue;
    double range;
    if (fan) {
      range = CastRayPastStatics(scene, origin, world_dirs_[i], c.range_max_m, static_ranges_[i]);
    } else {
      Eigen::Vector2d dir;
      if (sigma_bearing_rad > 0.0) {
        const double angle = T_world_robot.theta + angles_.angle_min_rad + i * angles_.angle_increment_rad +
                             sigma_bearing_rad * normal_(rng_);
        dir = Eigen::Vector2d(std::cos(angle), std::sin(angle));
      } else {
        dir = R_world_robot * beam_dirs_[i];
      }
      range = CastRay(scene, origin, dir, c.range_max_m);
    }
    if (range == kNoHit || range < c.range_min_m) continue;
    double measured = range;
    if (c.sigma_range_m > 0.0) measured += c.sigma_range_m * normal_(rng_);
    // A noisy hit stays a hit: keep it inside the sensor's reporting interval.
    scan.ranges_m[i] = std::clamp(measured, c.range_min_m, c.range_max_m);
    scan.valid[i] = 1;
  }
  return scan;
}

}  // namespace slambox
