#pragma once
// `icp-odometry`: LIDAR odometry by ICP, no loop closure. Each scan is registered to the
// previous scan (scan-to-scan, projection or kd-tree) or to a local map of the last
// scans (kd-tree), starting from the wheel odometry since the previous scan. Between
// scans the pose is propagated by odometry. KISS-ICP's adaptive gate bounds the pairs.
// Covariance: each scan's increment carries the ICP covariance (capped Hessian-based
// information, odometry's along degenerate directions; slam/edge_information.hpp),
// composed onto the previous scan's pose; odometry grows it between scans.
#include <deque>

#include "core/slam_module.hpp"
#include "slam/adaptive_threshold.hpp"
#include "slam/edge_information.hpp"
#include "slam/icp_params.hpp"
#include "slam/scan_points.hpp"

namespace slambox {

struct IcpOdometryConfig {
  /// Redescending weights (Geman-McClure): movers do not drag ICP.
  IcpConfig icp{.correspondence = IcpCorrespondence::kProjection, .robust_kernel = IcpRobustKernel::kGemanMcClure};
  bool adaptive_gate = true;      ///< KISS-ICP model-deviation gate instead of max_correspondence_m
  int local_map_scans = 0;        ///< 0 = scan-to-scan; N > 0 = scan-to-map of the last N scans (kd-tree)
  double local_map_voxel_m = 0.05;  ///< [m] voxel size of the local map
  double source_voxel_m = 0.0;    ///< [m] subsample the new scan (0 = every valid beam)
  double range_max_m = 0.0;       ///< [m] ignore returns beyond this (0 = the scan's range_max_m)
  double info_cap_sigma_xy_m = 0.002;      ///< [m] no scan increment more certain than this, translation
  double info_cap_sigma_theta_deg = 0.03;  ///< [deg] ... heading (both: ANEES 1.0-3.2 on loop, tunnel, symmetric, dynamic, seeds 0-2)
};
void BindParams(IcpOdometryConfig& c, ParamBinder& b);

class IcpOdometry : public SlamModule {
 public:
  explicit IcpOdometry(const IcpOdometryConfig& config);
  void Start(const StreamHeader& header) override;
  void OnOdometry(const OdometryEvent& odometry) override;
  void OnLaserScan(const LaserScanEvent& scan) override;
  Estimate Finish() override;

 private:
  void Record(double t_s);
  IcpTarget LocalMapTarget() const;

  IcpOdometryConfig config_;
  IcpConfig icp_;
  AdaptiveThreshold gate_;
  SE2 pose_;             ///< T_world_robot now
  SE2 last_scan_pose_;   ///< T_world_robot at the previous scan
  SE2 odometry_since_scan_;  ///< T_lastscan_robot by wheel odometry
  Eigen::Matrix3d odometry_cov_ = Eigen::Matrix3d::Zero();  ///< of odometry_since_scan_ (motion model)
  Eigen::Matrix3d pose_cov_ = Eigen::Matrix3d::Zero();       ///< of pose_
  Eigen::Matrix3d last_scan_cov_ = Eigen::Matrix3d::Zero();  ///< of last_scan_pose_
  std::array<double, 4> alpha_{};
  bool have_reference_ = false;
  IcpTarget reference_;  ///< previous scan (scan-to-scan)
  std::deque<std::vector<Eigen::Vector2d>> local_map_;  ///< world-frame points of recent scans
  Estimate estimate_;
};

ModuleInfo IcpOdometryModule();

}  // namespace slambox
