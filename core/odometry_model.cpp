#include "core/odometry_model.hpp"

#include <cmath>

namespace slambox {

OdometryIncrement Decompose(const SE2& delta) {
  OdometryIncrement u;
  u.trans = std::hypot(delta.x, delta.y);
  u.rot1 = u.trans < 1e-9 ? 0.0 : std::atan2(delta.y, delta.x);
  // Backward motion (a noisy in-place turn measures a tiny negative translation): a
  // negative trans with |rot1| <= pi/2 instead of rot1 near ±pi, which would inflate
  // the a1 rot1^2 noise term by orders of magnitude.
  if (std::abs(u.rot1) > M_PI / 2) {
    u.rot1 = NormalizeAngle(u.rot1 + M_PI);
    u.trans = -u.trans;
  }
  u.rot2 = NormalizeAngle(delta.theta - u.rot1);
  return u;
}

SE2 Compose(const OdometryIncrement& u) {
  return {u.trans * std::cos(u.rot1), u.trans * std::sin(u.rot1), u.rot1 + u.rot2};
}

Eigen::Matrix3d IncrementCovariance(const OdometryIncrement& u, const std::array<double, 4>& a) {
  const double r1 = u.rot1 * u.rot1, t = u.trans * u.trans, r2 = u.rot2 * u.rot2;
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
  M(0, 0) = a[0] * r1 + a[1] * t;
  M(1, 1) = a[2] * t + a[3] * (r1 + r2);
  M(2, 2) = a[0] * r2 + a[1] * t;
  return M;
}

MotionPrediction PredictMotion(const SE2& pose, const OdometryIncrement& u) {
  const double heading = pose.theta + u.rot1;
  const double c = std::cos(heading), s = std::sin(heading);
  MotionPrediction p;
  p.pose = SE2(pose.x + u.trans * c, pose.y + u.trans * s, pose.theta + u.rot1 + u.rot2);
  p.J_pose_pose << 1, 0, -u.trans * s,  //
      0, 1, u.trans * c,                //
      0, 0, 1;
  p.J_pose_increment << -u.trans * s, c, 0,  //
      u.trans * c, s, 0,                     //
      1, 0, 1;
  return p;
}

}  // namespace slambox
