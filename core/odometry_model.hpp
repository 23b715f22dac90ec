#pragma once
// Thrun's odometry motion model (Probabilistic Robotics, Sec. 5.4, Table 5.6): a relative
// motion is a rotation rot1, a straight translation trans, and a rotation rot2. The
// simulator samples its noise; filters propagate it with the Jacobians below.
#include <Eigen/Core>
#include <array>

#include "core/se2.hpp"

namespace slambox {

struct OdometryIncrement {
  double rot1 = 0.0;   ///< [rad]
  double trans = 0.0;  ///< [m]
  double rot2 = 0.0;   ///< [rad]
};

/// Decomposes a relative pose (robot frame) into (rot1, trans, rot2) with |rot1| <= pi/2:
/// backward motion has trans < 0. For a translation under 1e-9 m, rot1 = 0 and the whole
/// rotation goes to rot2.
OdometryIncrement Decompose(const SE2& delta);
/// The relative pose (trans cos rot1, trans sin rot1, rot1 + rot2).
SE2 Compose(const OdometryIncrement& u);

/// Covariance of (rot1, trans, rot2): diag(a1 rot1^2 + a2 trans^2,
/// a3 trans^2 + a4 (rot1^2 + rot2^2), a1 rot2^2 + a2 trans^2).
Eigen::Matrix3d IncrementCovariance(const OdometryIncrement& u, const std::array<double, 4>& alpha);

/// x' = x * Compose(u) and its Jacobians with respect to x = (x, y, theta) and
/// u = (rot1, trans, rot2) (Thrun Table 5.6 / 10.1's G_t and V_t).
struct MotionPrediction {
  SE2 pose;
  Eigen::Matrix3d J_pose_pose;
  Eigen::Matrix3d J_pose_increment;
};
MotionPrediction PredictMotion(const SE2& pose, const OdometryIncrement& u);

}  // namespace slambox
