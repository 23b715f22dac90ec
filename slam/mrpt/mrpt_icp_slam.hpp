#pragma once
// `mrpt-icp-slam`: MRPT 2.5's CMetricMapBuilderICP as a peer of slambox's ICP modules.
// Odometry (as MRPT's accumulated CObservationOdometry) predicts the pose; every scan
// that follows enough motion is aligned by CICP against the growing point map and the
// result replaces the pose; scans far enough apart are inserted into the map. No loop
// closure. The trajectory has a pose at every odometry and scan event (odometry-
// propagated between ICP corrections); map_points is MRPT's point map.
#include <memory>
#include <string>

#include "core/slam_module.hpp"
#include "slam/mrpt/mrpt_icp_params.hpp"

namespace slambox {

struct MrptIcpSlamConfig {
  MrptIcpParams icp{.max_iterations = 80, .smallest_threshold_dist_m = 0.05};  ///< the `icp_*` keys
  double min_icp_goodness = 0.40;         ///< fraction of paired points to accept a match
  double insertion_lin_distance_m = 0.5;  ///< motion before a scan joins the map
  double insertion_ang_distance_deg = 20.0;
  double localization_lin_distance_m = 0.2;  ///< motion before a scan is aligned (else odometry)
  double localization_ang_distance_deg = 5.0;
  double map_min_point_distance_m = 0.05;    ///< point-map insertion: drop closer points
};
void BindParams(MrptIcpSlamConfig& c, ParamBinder& b);

class MrptIcpSlam : public SlamModule {
 public:
  explicit MrptIcpSlam(const MrptIcpSlamConfig& config);
  ~MrptIcpSlam() override;
  void Start(const StreamHeader& header) override;
  void OnOdometry(const OdometryEvent& odometry) override;
  void OnLaserScan(const LaserScanEvent& scan) override;
  Estimate Finish() override;

  struct State;  ///< MRPT objects (pimpl: MRPT stays out of this header)

 private:
  void Record(double t_s);
  MrptIcpSlamConfig config_;
  std::unique_ptr<State> state_;
};

ModuleInfo MrptIcpSlamModule();

}  // namespace slambox
