#include "slam/mrpt/mrpt_ekf_slam.hpp"

#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt/slam/CRangeBearingKFSLAM2D.h>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "slam/mrpt/mrpt_convert.hpp"

namespace slambox {

namespace mb = mrpt_bridge;

void BindParams(MrptEkfSlamConfig& c, ParamBinder& b) {
  static const EnumNames<MrptDataAssociation> kNames = {{MrptDataAssociation::kNearestNeighbour, "nn"},
                                                       {MrptDataAssociation::kJcbb, "jcbb"}};
  b.Bind("data_association", c.data_association, kNames, "MRPT data association for landmarks without ids");
  b.Bind("association_chi2_quantile", c.association_chi2_quantile, "-", "chi-square quantile of the association gate");
  b.Bind("noise_scale", c.noise_scale, "-", "factor on the stream's sensor and odometry variances (1 = as configured)");
  b.Bind("min_sigma_xy_m", c.min_sigma_xy_m, "m", "floor on the odometry action's position std");
  b.Bind("min_sigma_theta_deg", c.min_sigma_theta_deg, "deg", "floor on the odometry action's heading std");
  b.Bind("max_landmarks", c.max_landmarks, "-",
         "stop with an error when MRPT's map holds more landmarks (it keeps every unpaired detection, clutter "
         "included, and a step's cost grows faster than n^2; 0 = no limit)");
}

struct MrptEkfSlam::State {
  mrpt::slam::CRangeBearingKFSLAM2D filter;
  LandmarkSensorConfig sensor;
  std::array<double, 4> alpha{};
  mb::OdometryAccumulator pending;  ///< odometry since the last EKF step
  bool anchored = false;
  SE2 anchor;                       ///< world pose of MRPT's origin
  PoseEstimate current;             ///< latest pose (world), with covariance
  Estimate estimate;
};

MrptEkfSlam::MrptEkfSlam(const MrptEkfSlamConfig& config) : config_(config) {}
MrptEkfSlam::~MrptEkfSlam() = default;

void MrptEkfSlam::Start(const StreamHeader& header) {
  mb::SeedMrptRandom(header.seed);
  state_ = std::make_unique<State>();
  State& s = *state_;
  s.sensor = header.sensors.landmarks.value_or(LandmarkSensorConfig{});
  s.alpha = header.sensors.odometry ? header.sensors.odometry->alpha : std::array<double, 4>{};
  for (double& a : s.alpha) a *= config_.noise_scale;
  auto& f = s.filter;
  f.setMinLoggingLevel(mrpt::system::LVL_ERROR);
  f.setVerbosityLevel(mrpt::system::LVL_ERROR);
  f.KF_options.method = mrpt::bayes::kfEKFNaive;
  f.KF_options.enable_profiler = false;
  const double k = std::sqrt(config_.noise_scale);
  f.options.std_sensor_range = static_cast<float>(k * s.sensor.sigma_range_m);
  f.options.std_sensor_yaw = static_cast<float>(k * s.sensor.sigma_bearing_deg * M_PI / 180.0);
  f.options.data_assoc_method = config_.data_association == MrptDataAssociation::kJcbb ? mrpt::slam::assocJCBB : mrpt::slam::assocNN;
  f.options.data_assoc_IC_chi2_thres = config_.association_chi2_quantile;
  f.options.create_simplemap = false;
  s.current = PoseEstimate{0.0, header.start_pose, Eigen::Matrix3d::Zero(), true};
  s.estimate.trajectory.push_back(s.current);
}

void MrptEkfSlam::OnOdometry(const OdometryEvent& odometry) {
  State& s = *state_;
  s.pending.Add(odometry, s.alpha);
  const OdometryIncrement u = Decompose(odometry.delta);
  const MotionPrediction p = PredictMotion(s.current.pose, u);
  s.current.t_s = odometry.t_s;
  s.current.pose = p.pose;
  s.current.covariance = p.J_pose_pose * s.current.covariance * p.J_pose_pose.transpose() +
                         p.J_pose_increment * IncrementCovariance(u, s.alpha) * p.J_pose_increment.transpose();
  s.estimate.trajectory.push_back(s.current);
}

void MrptEkfSlam::OnLandmarks(const LandmarkEvent& landmarks) {
  State& s = *state_;
  if (landmarks.observations.empty()) return;  // keep accumulating odometry
  auto actions = std::make_shared<mrpt::obs::CActionCollection>();
  if (!s.anchored) {  // MRPT's origin = the dead-reckoned pose now; no action (see header)
    s.anchored = true;
    s.anchor = s.current.pose;
  } else if (!s.pending.empty) {
    const mb::ActionNoiseFloor floor{config_.min_sigma_xy_m, config_.min_sigma_theta_deg * M_PI / 180.0};
    actions->insert(mb::ToMrptAction(s.pending, floor));
  }
  s.pending.Reset();
  auto frame = std::make_shared<mrpt::obs::CSensoryFrame>();
  frame->insert(std::make_shared<mrpt::obs::CObservationBearingRange>(mb::ToMrptBearingRange(landmarks, s.sensor)));
  s.filter.processActionObservation(actions, frame);

  mrpt::poses::CPosePDFGaussian pose;
  s.filter.getCurrentRobotPose(pose);
  Eigen::Matrix3d cov;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) cov(r, c) = pose.cov(r, c);
  s.current.t_s = landmarks.t_s;
  s.current.pose = mb::ToWorld(s.anchor, mb::FromMrpt(pose.mean));
  s.current.covariance = mb::CovarianceToWorld(s.anchor, cov);
  if (s.estimate.trajectory.back().t_s == landmarks.t_s)
    s.estimate.trajectory.back() = s.current;  // the update refines the odometry pose at this time
  else
    s.estimate.trajectory.push_back(s.current);
  const size_t mapped = s.filter.getNumberOfLandmarksInTheMap();
  s.estimate.diagnostics["landmarks_in_map"].push_back({landmarks.t_s, static_cast<double>(mapped)});
  if (config_.max_landmarks > 0 && mapped > static_cast<size_t>(config_.max_landmarks)) {
    char when[32];
    std::snprintf(when, sizeof when, "%.2f", landmarks.t_s);
    throw std::runtime_error(
        "mrpt-ekf-slam: MRPT's map holds " + std::to_string(mapped) + " landmarks at t = " + when +
        " s, more than max_landmarks = " + std::to_string(config_.max_landmarks) +
        " (MRPT's EKF keeps every detection it does not pair, clutter included, and each step's cost grows faster "
        "than the square of the landmarks; stopped rather than run for hours)\n  fix: --set "
        "algo.mrpt-ekf-slam.max_landmarks=N (0 = no limit) if the world has that many landmarks; compare the peer "
        "on a stream without clutter or with known ids");
  }
}

Estimate MrptEkfSlam::Finish() {
  State& s = *state_;
  if (s.anchored) {
    mrpt::poses::CPosePDFGaussian pose;
    std::vector<mrpt::math::TPoint2D> positions;
    std::map<unsigned int, mrpt::maps::CLandmark::TLandmarkID> ids;
    mrpt::math::CVectorDouble x;
    mrpt::math::CMatrixDouble P;
    s.filter.getCurrentState(pose, positions, ids, x, P);
    const Eigen::Matrix2d R = s.anchor.rotation();
    for (size_t i = 0; i < positions.size(); ++i) {
      LandmarkEstimate lm;
      const auto it = ids.find(static_cast<unsigned>(i));
      lm.id = it != ids.end() && it->second >= 0 ? static_cast<int>(it->second) : static_cast<int>(i);
      lm.position = s.anchor * Eigen::Vector2d(positions[i].x, positions[i].y);
      Eigen::Matrix2d cov;
      const int k = 3 + 2 * static_cast<int>(i);
      cov << P(k, k), P(k, k + 1), P(k + 1, k), P(k + 1, k + 1);
      lm.covariance = R * cov * R.transpose();
      lm.has_covariance = true;
      s.estimate.landmarks.push_back(lm);
    }
  }
  return std::move(s.estimate);
}

ModuleInfo MrptEkfSlamModule() {
  return MakeModuleInfo<MrptEkfSlam, MrptEkfSlamConfig>(
      "mrpt-ekf-slam", "MRPT 2.5 CRangeBearingKFSLAM2D: EKF SLAM with range-bearing landmarks",
      {.odometry = true, .landmarks = true}, &BindParams);
}

}  // namespace slambox
