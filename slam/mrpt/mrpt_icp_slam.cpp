#include "slam/mrpt/mrpt_icp_slam.hpp"

#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/poses/CPose3DPDF.h>
#include <mrpt/slam/CMetricMapBuilderICP.h>

#include "slam/mrpt/mrpt_convert.hpp"

namespace slambox {

namespace mb = mrpt_bridge;

void BindParams(MrptIcpSlamConfig& c, ParamBinder& b) {
  BindIcpParams(c.icp, b, "");
  b.Bind("min_icp_goodness", c.min_icp_goodness, "-", "minimum fraction of paired points to accept an ICP pose");
  b.Bind("insertion_lin_distance_m", c.insertion_lin_distance_m, "m", "motion before a scan is inserted into the map");
  b.Bind("insertion_ang_distance_deg", c.insertion_ang_distance_deg, "deg", "rotation before a scan is inserted into the map");
  b.Bind("localization_lin_distance_m", c.localization_lin_distance_m, "m", "motion before a scan is aligned by ICP");
  b.Bind("localization_ang_distance_deg", c.localization_ang_distance_deg, "deg", "rotation before a scan is aligned by ICP");
  b.Bind("map_min_point_distance_m", c.map_min_point_distance_m, "m", "point-map insertion: minimum distance between points");
}

struct MrptIcpSlam::State {
  mrpt::slam::CMetricMapBuilderICP builder;
  SE2 start;
  SE2 odometry;  ///< accumulated raw odometry in the start frame (MRPT's global odometry)
  double sigma_range_m = 0.01;
  Estimate estimate;
};

MrptIcpSlam::MrptIcpSlam(const MrptIcpSlamConfig& config) : config_(config) {}
MrptIcpSlam::~MrptIcpSlam() = default;

void MrptIcpSlam::Start(const StreamHeader& header) {
  mb::SeedMrptRandom(header.seed);
  state_ = std::make_unique<State>();
  State& s = *state_;
  s.start = header.start_pose;
  if (header.sensors.lidar) s.sigma_range_m = header.sensors.lidar->sigma_range_m;
  auto& b = s.builder;
  b.setMinLoggingLevel(mrpt::system::LVL_ERROR);
  b.setVerbosityLevel(mrpt::system::LVL_ERROR);
  b.ICP_options.matchAgainstTheGrid = false;
  b.ICP_options.insertionLinDistance = config_.insertion_lin_distance_m;
  b.ICP_options.insertionAngDistance = config_.insertion_ang_distance_deg * M_PI / 180.0;
  b.ICP_options.localizationLinDistance = config_.localization_lin_distance_m;
  b.ICP_options.localizationAngDistance = config_.localization_ang_distance_deg * M_PI / 180.0;
  b.ICP_options.minICPgoodnessToAccept = config_.min_icp_goodness;
  mrpt::maps::CSimplePointsMap::TMapDefinition points;
  points.insertionOpts.minDistBetweenLaserPoints = static_cast<float>(config_.map_min_point_distance_m);
  points.insertionOpts.isPlanarMap = true;
  b.ICP_options.mapInitializers.push_back(points);
  mb::SetIcpParams(config_.icp, b.ICP_params);
  // MRPT runs in the start frame (it starts at the identity); Record maps poses back.
  b.initialize();
  s.estimate.trajectory.push_back({0.0, s.start, Eigen::Matrix3d::Zero(), true});
}

void MrptIcpSlam::Record(double t_s) {
  State& s = *state_;
  mrpt::poses::CPose3D mean;
  s.builder.getCurrentPoseEstimation()->getMean(mean);
  const SE2 pose_start(mean.x(), mean.y(), mean.yaw());
  PoseEstimate pe{t_s, mb::ToWorld(s.start, pose_start), Eigen::Matrix3d::Zero(), false};
  if (!s.estimate.trajectory.empty() && s.estimate.trajectory.back().t_s == t_s)
    s.estimate.trajectory.back() = pe;  // a scan at the odometry's time refines that pose
  else
    s.estimate.trajectory.push_back(pe);
}

void MrptIcpSlam::OnOdometry(const OdometryEvent& odometry) {
  State& s = *state_;
  s.odometry = s.odometry * odometry.delta;
  auto obs = std::make_shared<mrpt::obs::CObservationOdometry>();
  obs->timestamp = mb::ToMrptTime(odometry.t_s);
  obs->odometry = mb::ToMrpt(s.odometry);
  obs->hasVelocities = false;
  s.builder.processObservation(obs);
  Record(odometry.t_s);
}

void MrptIcpSlam::OnLaserScan(const LaserScanEvent& scan) {
  State& s = *state_;
  auto obs = std::make_shared<mrpt::obs::CObservation2DRangeScan>(mb::ToMrptScan(scan, s.sigma_range_m));
  const size_t inserted_before = s.builder.getCurrentlyBuiltMapSize();
  s.builder.processObservation(obs);
  Record(scan.t_s);
  s.estimate.diagnostics["map_insertions"].push_back(
      {scan.t_s, static_cast<double>(s.builder.getCurrentlyBuiltMapSize() - inserted_before)});
}

Estimate MrptIcpSlam::Finish() {
  State& s = *state_;
  std::vector<float> xs, ys;
  s.builder.getCurrentMapPoints(xs, ys);
  for (size_t i = 0; i < xs.size(); ++i) s.estimate.map_points.push_back(s.start * Eigen::Vector2d(xs[i], ys[i]));
  return std::move(s.estimate);
}

ModuleInfo MrptIcpSlamModule() {
  return MakeModuleInfo<MrptIcpSlam, MrptIcpSlamConfig>(
      "mrpt-icp-slam", "MRPT 2.5 CMetricMapBuilderICP: ICP against a growing point map (no loop closure)",
      {.odometry = true, .lidar = true}, &BindParams);
}

}  // namespace slambox
