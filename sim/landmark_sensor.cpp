#include "sim/landmark_sensor.hpp"

#include <cmath>

#include "sim/seeding.hpp"

namespace slambox {

bool PostInLineOfSight(const RayScene& scene, const Eigen::Vector2d& robot_xy, const TrueLandmark& post) {
  const Eigen::Vector2d to_post = post.position - robot_xy;
  const double distance = to_post.norm();
  if (distance <= post.radius_m) return true;  // touching it
  const double first_hit = CastRay(scene, robot_xy, to_post / distance, distance);
  // Along the line of centres the post's own surface is at distance - radius.
  return first_hit >= distance - post.radius_m - 1e-9;
}

LandmarkSensor::LandmarkSensor(const LandmarkSensorConfig& config, std::uint64_t seed)
    : config_(config), rng_(MakeGenerator(seed, NoiseSource::kLandmarks)) {}

LandmarkEvent LandmarkSensor::Detect(double t_s, const SE2& T_world_robot, const std::vector<TrueLandmark>& posts,
                                     const RayScene& scene) {
  const LandmarkSensorConfig& c = config_;
  const double half_fov_rad = c.fov_deg * M_PI / 360.0;
  const double sigma_bearing_rad = c.sigma_bearing_deg * M_PI / 180.0;
  LandmarkEvent event;
  event.t_s = t_s;
  const Eigen::Vector2d xy = T_world_robot.translation();
  for (const TrueLandmark& post : posts) {
    const Eigen::Vector2d d = post.position - xy;
    const double range = d.norm();
    const double bearing = NormalizeAngle(std::atan2(d.y(), d.x()) - T_world_robot.theta);
    if (range > c.range_max_m || std::abs(bearing) > half_fov_rad) continue;
    if (!PostInLineOfSight(scene, xy, post)) continue;
    if (uniform_(rng_) >= c.detection_prob) continue;
    LandmarkObservation obs;
    obs.range_m = range + c.sigma_range_m * normal_(rng_);
    obs.bearing_rad = NormalizeAngle(bearing + sigma_bearing_rad * normal_(rng_));
    obs.id = c.known_ids ? post.id : -1;
    event.observations.push_back(obs);
  }
  if (c.clutter_per_scan > 0.0) {
    const int clutter = std::poisson_distribution<int>(c.clutter_per_scan)(rng_);
    for (int k = 0; k < clutter; ++k) {
      LandmarkObservation obs;
      obs.range_m = c.range_max_m * uniform_(rng_);
      obs.bearing_rad = NormalizeAngle(half_fov_rad * (2.0 * uniform_(rng_) - 1.0));
      event.observations.push_back(obs);
    }
  }
  return event;
}

}  // namespace slambox
