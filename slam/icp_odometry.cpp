#include "slam/icp_odometry.hpp"

#include <Eigen/LU>

#include "core/error.hpp"
#include "core/odometry_model.hpp"

namespace slambox {

void BindParams(IcpOdometryConfig& c, ParamBinder& b) {
  BindIcpParams(c.icp, b);
  b.Bind("adaptive_gate", c.adaptive_gate, "-", "KISS-ICP adaptive correspondence gate (3 sigma of model deviation)");
  b.Bind("local_map_scans", c.local_map_scans, "scans", "0 = scan-to-scan; N = register to a map of the last N scans");
  b.Bind("local_map_voxel_m", c.local_map_voxel_m, "m", "voxel size of the local map");
  b.Bind("source_voxel_m", c.source_voxel_m, "m", "subsample each new scan (0 = off)");
  b.Bind("range_max_m", c.range_max_m, "m", "ignore returns beyond this (0 = sensor maximum)");
  b.Bind("info_cap_sigma_xy_m", c.info_cap_sigma_xy_m, "m", "covariance: no scan increment more certain than this (translation)");
  b.Bind("info_cap_sigma_theta_deg", c.info_cap_sigma_theta_deg, "deg", "covariance: ... (heading)");
}

IcpOdometry::IcpOdometry(const IcpOdometryConfig& config)
    : config_(config), icp_(config.icp) {
  if (config_.local_map_scans < 0)
    throw InputError("--set algo.icp-odometry.local_map_scans", 0, "must be >= 0", "0 for scan-to-scan");
  if (!(config_.info_cap_sigma_xy_m > 0) || !(config_.info_cap_sigma_theta_deg > 0))
    throw InputError("--set algo.icp-odometry.info_cap_sigma_xy_m", 0, "information caps must be > 0",
                     "e.g. info_cap_sigma_xy_m=0.002, info_cap_sigma_theta_deg=0.03");
  if (config_.local_map_scans > 0) icp_.correspondence = IcpCorrespondence::kKdTree;  // a map has no beams
}

void IcpOdometry::Start(const StreamHeader& header) {
  estimate_ = Estimate{};
  pose_ = last_scan_pose_ = header.start_pose;
  odometry_since_scan_ = SE2();
  odometry_cov_.setZero();
  pose_cov_.setZero();
  last_scan_cov_.setZero();
  alpha_ = header.sensors.odometry ? header.sensors.odometry->alpha : std::array<double, 4>{};
  have_reference_ = false;
  local_map_.clear();
  gate_ = AdaptiveThreshold{};
  gate_.config.initial_gate_m = icp_.max_correspondence_m;
  if (header.sensors.lidar) gate_.config.max_range_m = header.sensors.lidar->range_max_m;
  if (config_.range_max_m > 0) gate_.config.max_range_m = config_.range_max_m;
  Record(0.0);
}

void IcpOdometry::Record(double t_s) {
  if (!estimate_.trajectory.empty() && estimate_.trajectory.back().t_s == t_s) {
    estimate_.trajectory.back().pose = pose_;
    estimate_.trajectory.back().covariance = pose_cov_;
    return;
  }
  estimate_.trajectory.push_back(PoseEstimate{t_s, pose_, pose_cov_, true});
}

void IcpOdometry::OnOdometry(const OdometryEvent& odometry) {
  // Thrun's odometry model (Table 5.6) on both the pose and the increment since the scan.
  const OdometryIncrement u = Decompose(odometry.delta);
  const Eigen::Matrix3d U = IncrementCovariance(u, alpha_);
  const MotionPrediction p = PredictMotion(pose_, u), q = PredictMotion(odometry_since_scan_, u);
  pose_cov_ = p.J_pose_pose * pose_cov_ * p.J_pose_pose.transpose() + p.J_pose_increment * U * p.J_pose_increment.transpose();
  odometry_cov_ = q.J_pose_pose * odometry_cov_ * q.J_pose_pose.transpose() + q.J_pose_increment * U * q.J_pose_increment.transpose();
  pose_ = pose_ * odometry.delta;
  odometry_since_scan_ = odometry_since_scan_ * odometry.delta;
  Record(odometry.t_s);
}

IcpTarget IcpOdometry::LocalMapTarget() const {
  std::vector<Eigen::Vector2d> all;
  for (const auto& scan : local_map_) all.insert(all.end(), scan.begin(), scan.end());
  std::vector<Eigen::Vector2d> thin;
  for (int k : VoxelSubsample(all, config_.local_map_voxel_m)) thin.push_back(all[static_cast<size_t>(k)]);
  return MakeCloudTarget(std::move(thin));
}

void IcpOdometry::OnLaserScan(const LaserScanEvent& scan) {
  const ScanPoints points =
      ScanToPoints(scan, {.range_max_m = config_.range_max_m, .voxel_size_m = config_.source_voxel_m});
  if (have_reference_) {
    IcpConfig icp = icp_;
    if (config_.adaptive_gate) icp.max_correspondence_m = CorrespondenceGate(gate_);
    const SE2 guess = odometry_since_scan_;  // T_lastscan_robot
    SE2 T_last_now = guess;
    IcpResult r;
    if (config_.local_map_scans > 0) {
      r = RegisterIcp(points.points, LocalMapTarget(), last_scan_pose_ * guess, icp);
      T_last_now = Between(last_scan_pose_, r.T_target_source);
    } else {
      r = RegisterIcp(points.points, reference_, guess, icp);
      T_last_now = r.T_target_source;
    }
    const bool failed = !r.converged && r.num_inliers < icp.min_inliers;
    if (failed) T_last_now = guess;  // ICP failed: odometry
    else if (config_.adaptive_gate) UpdateThreshold(gate_, guess, T_last_now);
    pose_ = last_scan_pose_ * T_last_now;
    // Scan-to-map ICP measures the pose in the map, whose own error is not modelled: the
    // increment's covariance is used the same way as scan-to-scan's.
    const InformationCaps caps{config_.info_cap_sigma_xy_m, config_.info_cap_sigma_theta_deg * M_PI / 180.0};
    const Eigen::Matrix3d increment_cov = failed ? odometry_cov_ : Eigen::Matrix3d(IcpEdgeInformation(r, odometry_cov_, caps).inverse());
    pose_cov_ = ComposeCovariance(last_scan_pose_, last_scan_cov_, T_last_now, increment_cov);
    auto& d = estimate_.diagnostics;
    d["icp_iterations"].emplace_back(scan.t_s, r.iterations);
    d["icp_inliers"].emplace_back(scan.t_s, r.num_inliers);
    d["hessian_min_eigenvalue"].emplace_back(scan.t_s, r.eigenvalues(0));
    d["degenerate"].emplace_back(scan.t_s, r.degenerate ? 1.0 : 0.0);
    d["icp_rms_residual_m"].emplace_back(scan.t_s, r.rms_residual_m);
    d["icp_gate_m"].emplace_back(scan.t_s, icp.max_correspondence_m);
  }
  last_scan_pose_ = pose_;
  last_scan_cov_ = pose_cov_;
  odometry_since_scan_ = SE2();
  odometry_cov_.setZero();
  if (config_.local_map_scans > 0) {
    std::vector<Eigen::Vector2d> world;
    world.reserve(points.points.size());
    for (const auto& p : points.points) world.push_back(pose_ * p);
    local_map_.push_back(std::move(world));
    while (static_cast<int>(local_map_.size()) > config_.local_map_scans) local_map_.pop_front();
  } else {
    IcpTargetConfig tc;
    tc.build_kd_tree = icp_.correspondence == IcpCorrespondence::kKdTree;
    reference_ = MakeScanTarget(points, scan, tc);
  }
  have_reference_ = true;
  Record(scan.t_s);
}

Estimate IcpOdometry::Finish() { return std::move(estimate_); }

ModuleInfo IcpOdometryModule() {
  return MakeModuleInfo<IcpOdometry, IcpOdometryConfig>(
      "icp-odometry", "LIDAR odometry: ICP scan-to-scan (or to a local map) from wheel-odometry guesses",
      {.odometry = true, .lidar = true}, &BindParams);
}

}  // namespace slambox
