#pragma once
// The range-bearing observation model of a point landmark seen from a 2D pose
// (Thrun, Prob. Robotics, eq. 6.40 / Table 10.1), its inverse for landmark
// initialization, and their Jacobians. Shared by EKF-SLAM, FastSLAM and GraphSLAM.
#include <Eigen/Core>

#include "core/se2.hpp"
#include "core/sensors.hpp"

namespace slambox {

/// z = (range [m], bearing [rad]) of landmark m from pose x:
/// range = |m - t|, bearing = wrap(atan2(m_y - y, m_x - x) - theta).
struct ObservationPrediction {
  Eigen::Vector2d z;
  Eigen::Matrix<double, 2, 3> J_z_pose;
  Eigen::Matrix2d J_z_landmark;
};
ObservationPrediction PredictObservation(const SE2& pose, const Eigen::Vector2d& landmark);

/// m = t + range (cos(theta + bearing), sin(theta + bearing)).
struct LandmarkInitialization {
  Eigen::Vector2d landmark;
  Eigen::Matrix<double, 2, 3> J_landmark_pose;
  Eigen::Matrix2d J_landmark_z;
};
LandmarkInitialization InverseObservation(const SE2& pose, const Eigen::Vector2d& z);

/// z_measured - z_predicted with the bearing difference wrapped to [-pi, pi).
inline Eigen::Vector2d Innovation(const Eigen::Vector2d& z_measured, const Eigen::Vector2d& z_predicted) {
  return {z_measured.x() - z_predicted.x(), NormalizeAngle(z_measured.y() - z_predicted.y())};
}

/// diag(sigma_range^2, sigma_bearing^2) in (m^2, rad^2).
Eigen::Matrix2d ObservationCovariance(const LandmarkSensorConfig& sensor);

}  // namespace slambox
