#include "slam/mrpt/mrpt_convert.hpp"

#include <cstring>

#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt/random/RandomGenerators.h>

#include <algorithm>
#include <cmath>

namespace slambox::mrpt_bridge {

void SetIcpParams(const MrptIcpParams& p, mrpt::slam::CICP::TConfigParams& out) {
  out.ICP_algorithm =
      p.algorithm == MrptIcpAlgorithm::kLevenbergMarquardt ? mrpt::slam::icpLevenbergMarquardt : mrpt::slam::icpClassic;
  out.maxIterations = static_cast<unsigned>(p.max_iterations);
  out.thresholdDist = p.threshold_dist_m;
  out.thresholdAng = p.threshold_ang_deg * M_PI / 180.0;
  out.ALFA = p.alfa;
  out.smallestThresholdDist = p.smallest_threshold_dist_m;
  out.corresponding_points_decimation = static_cast<uint32_t>(p.points_decimation);
}

void SeedMrptRandom(std::uint64_t seed) {
  // MRPT's generator takes a 32-bit seed; fold the high half in so seeds 2^32 apart differ.
  mrpt::random::getRandomGenerator().randomize(static_cast<uint32_t>(seed ^ (seed >> 32)));
}

void OdometryAccumulator::Add(const OdometryEvent& odometry, const std::array<double, 4>& alpha) {
  const OdometryIncrement u = Decompose(odometry.delta);
  const MotionPrediction p = PredictMotion(increment, u);
  covariance = p.J_pose_pose * covariance * p.J_pose_pose.transpose() +
               p.J_pose_increment * IncrementCovariance(u, alpha) * p.J_pose_increment.transpose();
  increment = p.pose;
  t_s = odometry.t_s;
  empty = false;
}

mrpt::obs::CActionRobotMovement2D ToMrptAction(const OdometryAccumulator& odometry, const ActionNoiseFloor& floor) {
  mrpt::obs::CActionRobotMovement2D action;
  action.timestamp = ToMrptTime(odometry.t_s);
  action.estimationMethod = mrpt::obs::CActionRobotMovement2D::emOdometry;
  action.motionModelConfiguration.modelSelection = mrpt::obs::CActionRobotMovement2D::mmGaussian;
  action.rawOdometryIncrementReading = ToMrpt(odometry.increment);
  mrpt::math::CMatrixDouble33 cov;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) cov(r, c) = odometry.covariance(r, c);
  cov(0, 0) += floor.sigma_xy_m * floor.sigma_xy_m;
  cov(1, 1) += floor.sigma_xy_m * floor.sigma_xy_m;
  cov(2, 2) += floor.sigma_theta_rad * floor.sigma_theta_rad;
  action.poseChange = mrpt::poses::CPosePDF::Ptr(mrpt::poses::CPosePDFGaussian::Create(ToMrpt(odometry.increment), cov));
  return action;
}

void UseMrptThrunModel(mrpt::obs::CActionRobotMovement2D& action, const std::array<double, 4>& alpha, double scale) {
  auto& m = action.motionModelConfiguration;
  m.modelSelection = mrpt::obs::CActionRobotMovement2D::mmThrun;
  m.thrunModel.alfa1_rot_rot = static_cast<float>(scale * std::sqrt(alpha[0]));
  m.thrunModel.alfa2_rot_trans = static_cast<float>(scale * std::sqrt(alpha[1]));
  m.thrunModel.alfa3_trans_trans = static_cast<float>(scale * std::sqrt(alpha[2]));
  m.thrunModel.alfa4_trans_rot = static_cast<float>(scale * std::sqrt(alpha[3]));
}

void UseMrptGaussianModel(mrpt::obs::CActionRobotMovement2D& action, const std::array<double, 4>& alpha, double scale,
                          const ActionNoiseFloor& floor) {
  auto& m = action.motionModelConfiguration;
  m.modelSelection = mrpt::obs::CActionRobotMovement2D::mmGaussian;
  m.gaussianModel.a1 = scale * std::sqrt(alpha[2]);  // m per m
  m.gaussianModel.a2 = scale * std::sqrt(alpha[3]);  // m per rad
  m.gaussianModel.a3 = scale * std::sqrt(alpha[1]);  // rad per m
  m.gaussianModel.a4 = scale * std::sqrt(alpha[0]);  // rad per rad
  m.gaussianModel.minStdXY = floor.sigma_xy_m;
  m.gaussianModel.minStdPHI = floor.sigma_theta_rad;
}

mrpt::obs::CObservation2DRangeScan ToMrptScan(const LaserScanEvent& scan, double sigma_range_m) {
  mrpt::obs::CObservation2DRangeScan out;
  const size_t n = scan.ranges_m.size();
  out.timestamp = ToMrptTime(scan.t_s);
  out.sensorLabel = "LIDAR";
  out.rightToLeft = true;
  const double aperture_rad = n > 1 ? scan.angle_increment_rad * static_cast<double>(n - 1) : 0.0;
  out.aperture = static_cast<float>(aperture_rad);
  out.sensorPose = mrpt::poses::CPose3D(0, 0, 0, scan.angle_min_rad + aperture_rad / 2, 0, 0);
  out.maxRange = static_cast<float>(scan.range_max_m);
  out.stdError = static_cast<float>(sigma_range_m);
  out.resizeScan(n);
  for (size_t i = 0; i < n; ++i) {
    const bool ok = i < scan.valid.size() && scan.valid[i] != 0;
    out.setScanRange(i, static_cast<float>(ok ? scan.ranges_m[i] : scan.range_max_m));
    out.setScanRangeValidity(i, ok);
  }
  return out;
}

mrpt::obs::CObservation2DRangeScan ToMrptScanForGrid(const LaserScanEvent& scan, double sigma_range_m, int upsampling) {
  const size_t k = static_cast<size_t>(std::max(1, upsampling));
  LaserScanEvent fine;
  fine.t_s = scan.t_s;
  fine.range_max_m = scan.range_max_m;
  fine.angle_min_rad = scan.angle_min_rad;
  fine.angle_increment_rad = scan.angle_increment_rad / static_cast<double>(k);
  fine.ranges_m.assign(scan.ranges_m.size() * k, scan.range_max_m);
  fine.valid.assign(scan.ranges_m.size() * k, 0);
  for (size_t i = 0; i < scan.ranges_m.size(); ++i) {
    fine.ranges_m[i * k] = scan.ranges_m[i];
    fine.valid[i * k] = i < scan.valid.size() ? scan.valid[i] : 0;
  }
  return ToMrptScan(fine, sigma_range_m);
}

namespace {
/// A bool field as MRPT deserialized it: the file's byte, copied without a check, so any of
/// 0-255 (fuzz_rawlog found 255, which is undefined behaviour to read as a bool). Its
/// object representation, read as a byte, is what the file meant: nonzero = true.
bool StoredBool(const bool& b) {
  unsigned char byte = 0;
  std::memcpy(&byte, &b, 1);
  return byte != 0;
}
}  // namespace

LaserScanEvent FromMrptScan(const mrpt::obs::CObservation2DRangeScan& scan, double t_s) {
  LaserScanEvent out;
  const size_t n = scan.getScanSize();
  out.t_s = t_s;
  out.range_max_m = scan.maxRange;
  const double aperture_rad = scan.aperture;
  out.angle_increment_rad = n > 1 ? aperture_rad / static_cast<double>(n - 1) : 0.0;
  // Beams start at -aperture/2 (right to left) or +aperture/2 (left to right); we keep
  // increasing angles, so a left-to-right scan is reversed.
  out.angle_min_rad = scan.sensorPose.yaw() - aperture_rad / 2;
  const bool right_to_left = StoredBool(scan.rightToLeft);
  for (size_t k = 0; k < n; ++k) {
    const size_t i = right_to_left ? k : n - 1 - k;
    out.ranges_m.push_back(scan.getScanRange(i));
    out.valid.push_back(scan.getScanRangeValidity(i) ? 1 : 0);
  }
  return out;
}

mrpt::obs::CObservationBearingRange ToMrptBearingRange(const LandmarkEvent& event, const LandmarkSensorConfig& cfg) {
  mrpt::obs::CObservationBearingRange out;
  out.timestamp = ToMrptTime(event.t_s);
  out.sensorLabel = "LANDMARKS";
  out.setSensorPose(mrpt::poses::CPose3D());
  out.minSensorDistance = 0.0f;
  out.maxSensorDistance = static_cast<float>(cfg.range_max_m);
  out.fieldOfView_yaw = static_cast<float>(cfg.fov_deg * M_PI / 180.0);
  out.fieldOfView_pitch = 0.0f;
  out.validCovariances = false;
  out.sensor_std_range = static_cast<float>(cfg.sigma_range_m);
  out.sensor_std_yaw = static_cast<float>(cfg.sigma_bearing_deg * M_PI / 180.0);
  out.sensor_std_pitch = 0.0f;
  for (const LandmarkObservation& o : event.observations) {
    mrpt::obs::CObservationBearingRange::TMeasurement m;
    m.range = static_cast<float>(o.range_m);
    m.yaw = static_cast<float>(o.bearing_rad);
    m.pitch = 0.0f;
    m.landmarkID = o.id;  // -1 is MRPT's INVALID_LANDMARK_ID: unknown association
    out.sensedData.push_back(m);
  }
  return out;
}

Eigen::Matrix3d CovarianceToWorld(const SE2& T_w_start, const Eigen::Matrix3d& cov_start) {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  R.topLeftCorner<2, 2>() = T_w_start.rotation();
  return R * cov_start * R.transpose();
}

}  // namespace slambox::mrpt_bridge
