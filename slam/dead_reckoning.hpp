#pragma once
// `odometry`: dead reckoning. Integrates wheel odometry from the true start pose and
// propagates the motion model's covariance (P' = G P G^T + V M V^T, Thrun Table 5.6).
#include "core/slam_module.hpp"

namespace slambox {

struct DeadReckoningConfig {
  /// Scales the motion-noise covariance of the stream's odometry model (1 = as configured).
  double noise_scale = 1.0;
};
void BindParams(DeadReckoningConfig& c, ParamBinder& b);

class DeadReckoning : public SlamModule {
 public:
  explicit DeadReckoning(const DeadReckoningConfig& config) : config_(config) {}
  void Start(const StreamHeader& header) override;
  void OnOdometry(const OdometryEvent& odometry) override;
  Estimate Finish() override;

 private:
  DeadReckoningConfig config_;
  std::array<double, 4> alpha_{};
  PoseEstimate current_;
  Estimate estimate_;
};

ModuleInfo DeadReckoningModule();

}  // namespace slambox
