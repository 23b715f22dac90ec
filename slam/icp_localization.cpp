#include "slam/icp_localization.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "core/error.hpp"
#include "core/odometry_model.hpp"
#include "slam/map_points.hpp"
#include "slam/map_visibility.hpp"
#include "slam/scan_points.hpp"

namespace slambox {

void BindParams(IcpLocalizationConfig& c, ParamBinder& b) {
  BindIcpParams(c.icp, b);
  b.Bind("map_spacing_m", c.map_spacing_m, "m", "spacing of the map points sampled along the walls");
  b.Bind("max_correction_m", c.max_correction_m, "m",
         "reject an ICP result farther than this from the prediction, or than 3 sigma of the prediction if larger (also the pair gate of a second try when fewer than half the points pair)");
  b.Bind("max_correction_deg", c.max_correction_deg, "deg", "reject an ICP result turned farther than this from the prediction, or than 3 sigma if larger");
  b.Bind("info_cap_sigma_xy_m", c.info_cap_sigma_xy_m, "m", "covariance: no scan more certain than this (translation)");
  b.Bind("info_cap_sigma_theta_deg", c.info_cap_sigma_theta_deg, "deg", "covariance: ... (heading)");
  b.Bind("visibility_margin_m", c.visibility_margin_m, "m",
         "register to the map points visible from the predicted pose (walls occlude), within this margin behind "
         "the nearest wall of their bearing; 0: the whole map");
}

IcpLocalization::IcpLocalization(const IcpLocalizationConfig& config)
    : config_(config), icp_(config.icp) {
  auto positive = [](double v, const char* name) {
    if (!(v > 0))
      throw InputError(std::string("--set algo.icp-localization.") + name, 0, "must be > 0", "give a positive value");
  };
  positive(config_.map_spacing_m, "map_spacing_m");
  positive(config_.max_correction_m, "max_correction_m");
  positive(config_.max_correction_deg, "max_correction_deg");
  positive(config_.info_cap_sigma_xy_m, "info_cap_sigma_xy_m");
  positive(config_.info_cap_sigma_theta_deg, "info_cap_sigma_theta_deg");
  if (!(config_.visibility_margin_m >= 0))
    throw InputError("--set algo.icp-localization.visibility_margin_m", 0, "must be >= 0", "e.g. 0.3; 0 uses the whole map");
}

void IcpLocalization::Start(const StreamHeader& header) {
  std::vector<Eigen::Vector2d> points = SampleWorldOutlines(header.world, config_.map_spacing_m);
  if (points.size() < 10)
    throw InputError(header.scenario_name, 0, "icp-localization needs a known map, and this stream's world has no walls",
                     "run it on a simulated scenario (a converted real log carries no map)");
  // Outlines sampled without noise: five neighbours give exact normals and keep corners sharp.
  map_ = MakeCloudTarget(std::move(points), {.normal_neighbors = 5, .build_kd_tree = true});
  world_ = header.world;
  range_max_m_ = header.sensors.lidar ? header.sensors.lidar->range_max_m : 30.0;
  alpha_ = header.sensors.odometry ? header.sensors.odometry->alpha : std::array<double, 4>{};
  pose_ = header.start_pose;
  covariance_.setZero();
  estimate_ = Estimate{};
  Record(0.0);
}

void IcpLocalization::Record(double t_s) {
  if (!estimate_.trajectory.empty() && estimate_.trajectory.back().t_s == t_s) estimate_.trajectory.pop_back();
  estimate_.trajectory.push_back(PoseEstimate{t_s, pose_, covariance_, true});
}

void IcpLocalization::OnOdometry(const OdometryEvent& odometry) {
  const OdometryIncrement u = Decompose(odometry.delta);
  const MotionPrediction p = PredictMotion(pose_, u);
  covariance_ = p.J_pose_pose * covariance_ * p.J_pose_pose.transpose() +
                p.J_pose_increment * IncrementCovariance(u, alpha_) * p.J_pose_increment.transpose();
  pose_ = pose_ * odometry.delta;
  Record(odometry.t_s);
}

void IcpLocalization::OnLaserScan(const LaserScanEvent& scan) {
  const ScanPoints points = ScanToPoints(scan, {});
  // The largest correction accepted: the configured one, or three standard deviations of
  // the prediction where it is less certain (along a corridor's axis the error of the
  // odometry builds up unseen and shows only at the next turn).
  const Eigen::Matrix2d cov_xy = covariance_.topLeftCorner<2, 2>();
  const double sigma_xy_m = std::sqrt(std::max(0.0, cov_xy.selfadjointView<Eigen::Upper>().eigenvalues().maxCoeff()));
  const double sigma_theta_deg = std::sqrt(std::max(0.0, covariance_(2, 2))) * 180.0 / M_PI;
  const double max_correction_m = std::max(config_.max_correction_m, 3.0 * sigma_xy_m);
  const double max_turn_deg = std::max(config_.max_correction_deg, 3.0 * sigma_theta_deg);
  // Where the prediction may be off by more than the pair gate, ICP starts with the gate
  // widened to the largest correction that would be accepted and is refined with the usual
  // one: at once when the prediction's 3 sigma is wider than the gate, else as a second try
  // when fewer than half the points found a wall within the gate (then the try that pairs
  // more points is kept).
  IcpConfig wide = icp_;
  wide.max_correspondence_m = std::max(icp_.max_correspondence_m, max_correction_m);
  // ... and its robust kernel as wide as its gate: under the fine kernel (Geman-McClure at
  // 5 cm) a pair 0.5 m off weighs ~1e-4, so the very points that show a large error (a leg's
  // end wall) would have no say, and their direction would stay degenerate.
  wide.robust_scale_m = std::max(icp_.robust_scale_m, wide.max_correspondence_m);
  // The map as seen from the prediction: the widest accepted correction and the gate farther.
  IcpTarget visible;
  if (config_.visibility_margin_m > 0) {
    const MapVisibilitySetting seen{.range_max_m = range_max_m_ + max_correction_m + wide.max_correspondence_m,
                                    .depth_margin_m = config_.visibility_margin_m};
    visible = SubsetTarget(map_, VisibleMapPoints(world_, map_.points, pose_.translation(), seen));
  }
  const IcpTarget& target = config_.visibility_margin_m > 0 ? visible : map_;
  auto wide_then_fine = [&] {
    return RegisterIcp(points.points, target, RegisterIcp(points.points, target, pose_, wide).T_target_source, icp_);
  };
  IcpResult r;
  if (3.0 * sigma_xy_m > icp_.max_correspondence_m) {
    r = wide_then_fine();
  } else {
    r = RegisterIcp(points.points, target, pose_, icp_);
    if (2 * r.num_inliers < static_cast<int>(points.points.size())) {
      IcpResult second = wide_then_fine();
      if (second.num_inliers > r.num_inliers) r = std::move(second);
    }
  }
  const double correction_m = (r.T_target_source.translation() - pose_.translation()).norm();
  const double turn_deg = std::abs(NormalizeAngle(r.T_target_source.theta - pose_.theta)) * 180.0 / M_PI;
  const bool ok = r.num_inliers >= icp_.min_inliers && correction_m <= max_correction_m && turn_deg <= max_turn_deg;
  if (ok) {
    // The scan measures the absolute pose; where ICP is degenerate the prediction's
    // information is kept (IcpEdgeInformation projects it onto those directions).
    const InformationCaps caps{config_.info_cap_sigma_xy_m, config_.info_cap_sigma_theta_deg * M_PI / 180.0};
    pose_ = r.T_target_source;
    covariance_ = IcpEdgeInformation(r, covariance_, caps).inverse();
  }
  auto& d = estimate_.diagnostics;
  d["icp_iterations"].emplace_back(scan.t_s, r.iterations);
  d["icp_inliers"].emplace_back(scan.t_s, r.num_inliers);
  d["hessian_min_eigenvalue"].emplace_back(scan.t_s, r.eigenvalues(0));
  d["degenerate"].emplace_back(scan.t_s, r.degenerate ? 1.0 : 0.0);
  d["scan_accepted"].emplace_back(scan.t_s, ok ? 1.0 : 0.0);
  Record(scan.t_s);
}

Estimate IcpLocalization::Finish() { return std::move(estimate_); }

ModuleInfo IcpLocalizationModule() {
  return MakeModuleInfo<IcpLocalization, IcpLocalizationConfig>(
      "icp-localization", "pose tracking in the known map (the world's walls) by scan-to-map ICP from odometry",
      {.odometry = true, .lidar = true, .map = true}, &BindParams);
}

}  // namespace slambox
