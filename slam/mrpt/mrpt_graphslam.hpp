#pragma once
// `mrpt-graphslam`: MRPT 2.5's pose-graph LIDAR SLAM (mrpt::graphslam::CGraphSlamEngine
// over CNetworkOfPoses2DInf) with the deciders and optimizer of MRPT's own
// `graphslam-engine` configuration laser_odometry_LC.ini: CFixedIntervalsNRD (a node
// every registration_max_distance_m / registration_max_angle_deg of odometry),
// CLoopCloserERD (ICP edges to the previous nodes, loop closures found by map
// partitioning and checked for consistency) and CLevMarqGSO (Levenberg-Marquardt over
// the nodes near the newest one, the whole graph after a loop closure). The fair
// counterpart of icp-poseslam.
//
// The defaults are read from the installed .ini at run time (ReadMrptGraphSlamIni): the
// module's parameters are that file's values, and the engine is configured with the file's
// text with only the parameters set here replaced (WriteMrptGraphSlamIni); verbosity is
// set to errors only and visualization is off (headless engine).
//
// Odometry between two scans is one CActionRobotMovement2D with the Thrun-model covariance
// (the action-observation format), the scan its CSensoryFrame. The trajectory has a pose
// at every scan: at Finish, the optimized pose of the last node registered at or before
// the scan, composed with the odometry since that node's scan. map_points are the
// occupied cells of the engine's grid map (every node's scan at its optimized pose).
//
// Cost: MRPT's per-scan work grows with the graph (see slam/mrpt/README.md for the
// measured times); it is therefore named only, never run by `--algo all`.
#include <memory>
#include <string>

#include "core/slam_module.hpp"

namespace slambox {

struct MrptGraphSlamConfig {
  // [NodeRegistrationDeciderParameters]
  double registration_max_distance_m = 0.1;  ///< registration_max_distance
  double registration_max_angle_deg = 15.0;  ///< registration_max_angle
  // [EdgeRegistrationDeciderParameters], [GeneralConfiguration] LC_min_nodeid_diff
  int icp_prev_nodes = 10;                   ///< prev_nodes_for_ICP
  int lc_min_nodeid_diff = 20;               ///< LC_min_nodeid_diff
  int lc_min_remote_nodes = 3;               ///< LC_min_remote_nodes
  double lc_eigenvalues_ratio_thresh = 2.0;  ///< LC_eigenvalues_ratio_thresh
  double partition_threshold = 0.7;          ///< partitionThreshold
  // [OptimizerParameters]
  double optimization_distance_m = 1.5;      ///< optimization_distance
  int optimizer_max_iterations = 100;        ///< max_iterations
  // [ICP]
  int icp_max_iterations = 100;              ///< maxIterations
  double icp_threshold_dist_m = 0.3;         ///< thresholdDist
  double icp_threshold_ang_deg = 5.0;        ///< thresholdAng_DEG
  double icp_alfa = 0.8;                     ///< ALFA
  double icp_smallest_threshold_dist_m = 0.05;  ///< smallestThresholdDist
  int icp_points_decimation = 5;             ///< corresponding_points_decimation
  bool icp_levenberg_marquardt = true;       ///< ICP_algorithm: icpLevenbergMarquardt (true) or icpClassic
  // slambox's side (not in the .ini)
  double occupied_below_free_prob = 0.3;     ///< a grid cell is a map point when p(free) < this
};
void BindParams(MrptGraphSlamConfig& c, ParamBinder& b);

/// The laser_odometry_LC.ini found at configure time (Debian mrpt-common).
std::string MrptGraphSlamIniPath();
/// The module's parameters as the .ini at `path` sets them (MRPT's own reader, so exactly
/// what the engine would read; a key the file lacks keeps MRPT's code default). Throws
/// InputError naming the file when it is missing.
MrptGraphSlamConfig ReadMrptGraphSlamIni(const std::string& path);
/// The text of the .ini at `path` with the parameters of `config` written over its values,
/// every class_verbosity set to errors only (3), and the visualization switches off.
std::string WriteMrptGraphSlamIni(const std::string& path, const MrptGraphSlamConfig& config);

class MrptGraphSlam : public SlamModule {
 public:
  explicit MrptGraphSlam(const MrptGraphSlamConfig& config, std::string ini_path = MrptGraphSlamIniPath());
  ~MrptGraphSlam() override;
  void Start(const StreamHeader& header) override;
  void OnOdometry(const OdometryEvent& odometry) override;
  void OnLaserScan(const LaserScanEvent& scan) override;
  Estimate Finish() override;

  struct State;  ///< MRPT objects (pimpl: MRPT stays out of this header)

 private:
  MrptGraphSlamConfig config_;
  std::string ini_path_;
  std::unique_ptr<State> state_;
};

/// Named only (ModuleInfo::in_all = false): too slow for `--algo all`.
ModuleInfo MrptGraphSlamModule();

}  // namespace slambox
