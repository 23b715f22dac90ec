#pragma once
// Landmark (post) detector: range and bearing to each post's centre that lies within
// range_max_m and the field of view and in line of sight (walls, movers and other posts
// occlude), detected with probability detection_prob, with Gaussian range/bearing noise.
// Plus Poisson(clutter_per_scan) false detections uniform in range and field of view.
#include <cstdint>
#include <random>
#include <vector>

#include "core/sensors.hpp"
#include "core/stream.hpp"
#include "sim/ray_caster.hpp"

namespace slambox {

/// True if nothing in `scene` lies between the robot and the post's near surface.
bool PostInLineOfSight(const RayScene& scene, const Eigen::Vector2d& robot_xy, const TrueLandmark& post);

class LandmarkSensor {
 public:
  LandmarkSensor(const LandmarkSensorConfig& config, std::uint64_t seed);
  LandmarkEvent Detect(double t_s, const SE2& T_world_robot, const std::vector<TrueLandmark>& posts,
                       const RayScene& scene);

 private:
  LandmarkSensorConfig config_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  std::uniform_real_distribution<double> uniform_{0.0, 1.0};
};

}  // namespace slambox
