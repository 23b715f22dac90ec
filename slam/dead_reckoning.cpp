#include "slam/dead_reckoning.hpp"

#include "core/odometry_model.hpp"

namespace slambox {

void BindParams(DeadReckoningConfig& c, ParamBinder& b) {
  b.Bind("noise_scale", c.noise_scale, "-", "factor on the odometry model's covariance (1 = as configured)");
}

void DeadReckoning::Start(const StreamHeader& header) {
  alpha_ = header.sensors.odometry ? header.sensors.odometry->alpha : std::array<double, 4>{};
  current_ = PoseEstimate{0.0, header.start_pose, Eigen::Matrix3d::Zero(), true};
  estimate_ = Estimate{};
  estimate_.trajectory.push_back(current_);
}

void DeadReckoning::OnOdometry(const OdometryEvent& odometry) {
  const OdometryIncrement u = Decompose(odometry.delta);
  const MotionPrediction p = PredictMotion(current_.pose, u);
  const Eigen::Matrix3d M = config_.noise_scale * IncrementCovariance(u, alpha_);
  current_.t_s = odometry.t_s;
  current_.pose = p.pose;
  current_.covariance = p.J_pose_pose * current_.covariance * p.J_pose_pose.transpose() +
                        p.J_pose_increment * M * p.J_pose_increment.transpose();
  estimate_.trajectory.push_back(current_);
}

Estimate DeadReckoning::Finish() { return std::move(estimate_); }

ModuleInfo DeadReckoningModule() {
  ModuleInfo info = MakeModuleInfo<DeadReckoning, DeadReckoningConfig>(
      "odometry", "dead reckoning from wheel odometry, covariance from the motion model", {.odometry = true},
      &BindParams);
  info.baseline = true;  // what every SLAM module is compared with
  return info;
}

}  // namespace slambox
