#pragma once
// `icp-localization`: pose tracking in a known map. The map is the stream's world (walls
// and posts, sampled into points with normals and a kd-tree); each scan is registered to
// it by ICP from the odometry-predicted pose; between scans the pose follows odometry.
// Covariance: the capped ICP covariance at scans (along directions ICP cannot see, e.g.
// a corridor's axis, the predicted covariance stays), Thrun's odometry model between them.
// A scan ICP rejects (too few pairs, or a correction beyond max_correction_m or
// max_correction_deg, or 3 sigma of the prediction where that is larger) leaves the prediction, so a mover or a dropout does not teleport the
// robot. When fewer than half the scan's points pair, ICP is tried again with a pair gate as
// wide as the largest accepted correction, so an error grown along a corridor's axis is caught
// when the next corridor makes it observable. The map points a scan may pair with are those
// visible from the predicted pose (slam/map_visibility.hpp), so a surface behind a wall (a map
// image's outer border, one wall thickness behind the inner one) never attracts a scan.
#include "core/slam_module.hpp"
#include "slam/edge_information.hpp"
#include "slam/icp_params.hpp"

namespace slambox {

struct IcpLocalizationConfig {
  /// Redescending weights (Geman-McClure): movers are not in the map.
  IcpConfig icp{.correspondence = IcpCorrespondence::kKdTree, .robust_kernel = IcpRobustKernel::kGemanMcClure,
                .max_correspondence_m = 0.3};
  double map_spacing_m = 0.05;           ///< [m] spacing of the map points along walls
  double max_correction_m = 0.5;         ///< [m] a larger ICP correction of the prediction is rejected
  double max_correction_deg = 10.0;      ///< [deg] ... a larger turn too
  double info_cap_sigma_xy_m = 0.005;    ///< [m] no scan more certain than this, translation
  double info_cap_sigma_theta_deg = 0.1; ///< [deg] ... heading
  /// Register each scan only to the map points visible from the predicted pose (walls as
  /// occluders, slam/map_visibility.hpp), within this margin behind the nearest wall of
  /// their bearing; 0 registers to the whole map.
  double visibility_margin_m = 0.3;
};
void BindParams(IcpLocalizationConfig& c, ParamBinder& b);

class IcpLocalization : public SlamModule {
 public:
  explicit IcpLocalization(const IcpLocalizationConfig& config);
  void Start(const StreamHeader& header) override;
  void OnOdometry(const OdometryEvent& odometry) override;
  void OnLaserScan(const LaserScanEvent& scan) override;
  Estimate Finish() override;

 private:
  void Record(double t_s);

  IcpLocalizationConfig config_;
  IcpConfig icp_;
  IcpTarget map_;
  World world_;  ///< the map's walls, as occluders
  double range_max_m_ = 30.0;
  std::array<double, 4> alpha_{};
  SE2 pose_;
  Eigen::Matrix3d covariance_ = Eigen::Matrix3d::Zero();
  Estimate estimate_;
};

ModuleInfo IcpLocalizationModule();

}  // namespace slambox
