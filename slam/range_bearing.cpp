#include "slam/range_bearing.hpp"

#include <cmath>

namespace slambox {

ObservationPrediction PredictObservation(const SE2& pose, const Eigen::Vector2d& landmark) {
  const double dx = landmark.x() - pose.x, dy = landmark.y() - pose.y;
  const double q = dx * dx + dy * dy, r = std::sqrt(q);
  ObservationPrediction p;
  p.z = {r, NormalizeAngle(std::atan2(dy, dx) - pose.theta)};
  p.J_z_pose << -dx / r, -dy / r, 0.0,  //
      dy / q, -dx / q, -1.0;
  p.J_z_landmark << dx / r, dy / r,  //
      -dy / q, dx / q;
  return p;
}

LandmarkInitialization InverseObservation(const SE2& pose, const Eigen::Vector2d& z) {
  const double r = z.x(), heading = pose.theta + z.y();
  const double c = std::cos(heading), s = std::sin(heading);
  LandmarkInitialization init;
  init.landmark = {pose.x + r * c, pose.y + r * s};
  init.J_landmark_pose << 1.0, 0.0, -r * s,  //
      0.0, 1.0, r * c;
  init.J_landmark_z << c, -r * s,  //
      s, r * c;
  return init;
}

Eigen::Matrix2d ObservationCovariance(const LandmarkSensorConfig& sensor) {
  const double sb = sensor.sigma_bearing_deg * M_PI / 180.0;
  return Eigen::Vector2d(sensor.sigma_range_m * sensor.sigma_range_m, sb * sb).asDiagonal();
}

}  // namespace slambox
