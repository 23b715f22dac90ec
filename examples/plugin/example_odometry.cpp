// `example-odometry`: dead reckoning as an out-of-tree module plugin. It integrates wheel
// odometry from the start pose and propagates the motion model's covariance
// (P' = G P Gᵀ + V M Vᵀ, Thrun Table 5.6), the same computation as the built-in
// `odometry`, so both give bit-identical metrics (tests/plugins/example_plugin_test.sh).
#include "core/odometry_model.hpp"
#include "core/plugin.hpp"

namespace {

using namespace slambox;

struct ExampleOdometryConfig {
  double noise_scale = 1.0;  ///< factor on the odometry model's covariance
};

void BindParams(ExampleOdometryConfig& c, ParamBinder& b) {
  b.Bind("noise_scale", c.noise_scale, "-", "factor on the odometry model's covariance (1 = as configured)");
}

class ExampleOdometry : public SlamModule {
 public:
  explicit ExampleOdometry(const ExampleOdometryConfig& config) : config_(config) {}

  void Start(const StreamHeader& header) override {
    alpha_ = header.sensors.odometry ? header.sensors.odometry->alpha : std::array<double, 4>{};
    current_ = PoseEstimate{0.0, header.start_pose, Eigen::Matrix3d::Zero(), true};
    estimate_ = Estimate{};
    estimate_.trajectory.push_back(current_);
  }

  void OnOdometry(const OdometryEvent& odometry) override {
    const OdometryIncrement u = Decompose(odometry.delta);
    const MotionPrediction p = PredictMotion(current_.pose, u);
    const Eigen::Matrix3d M = config_.noise_scale * IncrementCovariance(u, alpha_);
    current_.t_s = odometry.t_s;
    current_.pose = p.pose;
    current_.covariance = p.J_pose_pose * current_.covariance * p.J_pose_pose.transpose() +
                          p.J_pose_increment * M * p.J_pose_increment.transpose();
    estimate_.trajectory.push_back(current_);
  }

  Estimate Finish() override { return std::move(estimate_); }

 private:
  ExampleOdometryConfig config_;
  std::array<double, 4> alpha_{};
  PoseEstimate current_;
  Estimate estimate_;
};

std::vector<ModuleInfo> Modules() {
  return {MakeModuleInfo<ExampleOdometry, ExampleOdometryConfig>(
      "example-odometry", "dead reckoning as an out-of-tree plugin (examples/plugin)", {.odometry = true},
      &BindParams)};
}

}  // namespace

SLAMBOX_PLUGIN("example-odometry", Modules)
