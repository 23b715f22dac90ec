#include "slam/mrpt/mrpt_rbpf_slam.hpp"
#include "slam/mrpt/mrpt_rbpf_options.hpp"

#include <algorithm>

#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/slam/CMetricMapBuilderRBPF.h>

#include "slam/mrpt/mrpt_convert.hpp"

namespace slambox {

namespace mb = mrpt_bridge;

namespace {
mrpt::bayes::CParticleFilter::TParticleResamplingAlgorithm ToMrpt(MrptResampling r) {
  using PF = mrpt::bayes::CParticleFilter;
  switch (r) {
    case MrptResampling::kMultinomial: return PF::prMultinomial;
    case MrptResampling::kResidual: return PF::prResidual;
    case MrptResampling::kStratified: return PF::prStratified;
    case MrptResampling::kSystematic: break;
  }
  return PF::prSystematic;
}
}  // namespace

void BindParams(MrptRbpfSlamConfig& c, ParamBinder& b) {
  static const EnumNames<MrptProposal> kNames = {{MrptProposal::kOptimal, "optimal"},
                                                {MrptProposal::kStandard, "standard"}};
  static const EnumNames<MrptRbpfMap> kMaps = {{MrptRbpfMap::kGrid, "grid"}, {MrptRbpfMap::kPoints, "points"}};
  static const EnumNames<MrptResampling> kResampling = {{MrptResampling::kMultinomial, "multinomial"},
                                                        {MrptResampling::kResidual, "residual"},
                                                        {MrptResampling::kStratified, "stratified"},
                                                        {MrptResampling::kSystematic, "systematic"}};
  b.Bind("proposal", c.proposal, kNames, "pfOptimalProposal (scan matching) or pfStandardProposal");
  b.Bind("map", c.map, kMaps, "each particle's map: occupancy grid or point map (ICP-based RBPF with proposal=optimal)");
  b.Bind("particles", c.particles, "-", "number of particles (one map each)", AtLeast(1));
  b.Bind("resampling", c.resampling, kResampling, "MRPT resampling scheme (the ini's resamplingMethod 0..3)");
  b.Bind("resample_ess_ratio", c.resample_ess_ratio, "-", "resample when ESS/N is below this (MRPT BETA)");
  b.Bind("grid_resolution_m", c.grid_resolution_m, "m", "occupancy grid cell size");
  b.Bind("localize_lin_distance_m", c.localize_lin_distance_m, "m", "motion between particle-filter steps");
  b.Bind("localize_ang_distance_deg", c.localize_ang_distance_deg, "deg", "rotation between particle-filter steps");
  b.Bind("insertion_lin_distance_m", c.insertion_lin_distance_m, "m", "motion between map insertions");
  b.Bind("insertion_ang_distance_deg", c.insertion_ang_distance_deg, "deg", "rotation between map insertions");
  b.Bind("likelihood_sigma_hit_m", c.likelihood_sigma_hit_m, "m", "likelihood-field std of a beam end point");
  b.Bind("likelihood_decimation", c.likelihood_decimation, "-", "use every n-th beam in the likelihood");
  b.Bind("icp_min_quality", c.icp_min_quality, "-", "optimal proposal: ICPGlobalAlign_MinQuality (MRPT 2.5 only warns below it and keeps the ICP pose)");
  b.Bind("motion_noise_scale", c.motion_noise_scale, "-", "factor on MRPT's Gaussian-model stds (scale * sqrt(a_i))");
  b.Bind("grid_beam_upsampling", c.grid_beam_upsampling, "-", "invalid beams between real ones: bounds MRPT's grid-insertion angle error");
  b.Bind("occupied_below_free_prob", c.occupied_below_free_prob, "-", "grid cells with p(free) below this are map points");
  BindIcpParams(c.icp, b, "optimal proposal: ");
  b.Bind("points_min_distance_m", c.points_min_distance_m, "m", "map=points: insertion minDistBetweenLaserPoints", AtLeast(0));
  b.Bind("points_likelihood_var_m2", c.points_likelihood_var_m2, "m^2", "map=points: likelihood sigma_dist, a variance (log p = -mean clipped d^2 / this)", Above(0));
  b.Bind("points_likelihood_max_corr_m", c.points_likelihood_max_corr_m, "m", "map=points: likelihood max_corr_distance (distances clipped here)", Above(0));
  b.Bind("points_likelihood_decimation", c.points_likelihood_decimation, "-", "map=points: likelihood uses every n-th scan point", AtLeast(1));
}

mrpt::slam::CMetricMapBuilderRBPF::TConstructionOptions MakeMrptRbpfOptions(const MrptRbpfSlamConfig& c) {
  mrpt::slam::CMetricMapBuilderRBPF::TConstructionOptions o;
  o.verbosity_level = mrpt::system::LVL_ERROR;
  o.insertionLinDistance = static_cast<float>(c.insertion_lin_distance_m);
  o.insertionAngDistance = static_cast<float>(c.insertion_ang_distance_deg * M_PI / 180.0);
  o.localizeLinDistance = static_cast<float>(c.localize_lin_distance_m);
  o.localizeAngDistance = static_cast<float>(c.localize_ang_distance_deg * M_PI / 180.0);
  o.PF_options.PF_algorithm = c.proposal == MrptProposal::kOptimal ? mrpt::bayes::CParticleFilter::pfOptimalProposal
                                                                  : mrpt::bayes::CParticleFilter::pfStandardProposal;
  o.PF_options.resamplingMethod = ToMrpt(c.resampling);
  o.PF_options.sampleSize = static_cast<unsigned>(c.particles);
  o.PF_options.adaptiveSampleSize = false;
  o.PF_options.BETA = c.resample_ess_ratio;
  // pfOptimalProposal aligns the scan against the particle's map of this kind (MRPT's
  // pfOptimalProposal_mapSelection: 0 = grid, 3 = points); it asserts that map exists.
  o.predictionOptions.pfOptimalProposal_mapSelection = c.map == MrptRbpfMap::kPoints ? 3 : 0;
  o.predictionOptions.ICPGlobalAlign_MinQuality = static_cast<float>(c.icp_min_quality);
  mrpt_bridge::SetIcpParams(c.icp, o.predictionOptions.icp_params);
  if (c.map == MrptRbpfMap::kPoints) {
    // gridmapping_RBPF_ICPbased_intel.ini's [..._pointsMap_00_*]: planar, no fusion.
    mrpt::maps::CSimplePointsMap::TMapDefinition points;
    points.insertionOpts.minDistBetweenLaserPoints = static_cast<float>(c.points_min_distance_m);
    points.insertionOpts.isPlanarMap = true;
    points.insertionOpts.fuseWithExisting = false;
    points.likelihoodOpts.sigma_dist = c.points_likelihood_var_m2;
    points.likelihoodOpts.max_corr_distance = c.points_likelihood_max_corr_m;
    points.likelihoodOpts.decimation = static_cast<uint32_t>(c.points_likelihood_decimation);
    o.mapsInitializers.push_back(points);
  } else {
    mrpt::maps::COccupancyGridMap2D::TMapDefinition grid;
    grid.min_x = grid.min_y = -10.0f;
    grid.max_x = grid.max_y = 10.0f;  // grows as scans are inserted
    grid.resolution = static_cast<float>(c.grid_resolution_m);
    grid.insertionOpts.maxDistanceInsertion = 15.0f;
    grid.insertionOpts.decimation = static_cast<uint16_t>(c.grid_beam_upsampling);  // the valid beams only
    grid.likelihoodOpts.likelihoodMethod = mrpt::maps::COccupancyGridMap2D::lmLikelihoodField_Thrun;
    grid.likelihoodOpts.LF_stdHit = static_cast<float>(c.likelihood_sigma_hit_m);
    grid.likelihoodOpts.LF_decimation = static_cast<uint32_t>(c.likelihood_decimation);
    o.mapsInitializers.push_back(grid);
  }
  return o;
}

struct MrptRbpfSlam::State {
  std::unique_ptr<mrpt::slam::CMetricMapBuilderRBPF> builder;
  std::array<double, 4> alpha{};
  double sigma_range_m = 0.01;
  SE2 start;
  mb::OdometryAccumulator pending;  ///< odometry since the last scan
  std::vector<double> step_t_s;     ///< time of each path entry (entry 0: the start)
  SE2 odometry;                     ///< raw odometry composed since the start (start frame)
  std::vector<SE2> step_odometry;   ///< `odometry` at each path entry
  /// Every scan: its time, odometry, and the path entry at or before it; Finish places it
  /// on the final path by the odometry since that entry (a pose at every scan).
  struct ScanRecord {
    double t_s;
    SE2 odometry;
    size_t step;
  };
  std::vector<ScanRecord> scans;
  Estimate estimate;
};

MrptRbpfSlam::MrptRbpfSlam(const MrptRbpfSlamConfig& config) : config_(config) {}
MrptRbpfSlam::~MrptRbpfSlam() = default;

void MrptRbpfSlam::Start(const StreamHeader& header) {
  mb::SeedMrptRandom(header.seed);
  state_ = std::make_unique<State>();
  State& s = *state_;
  s.start = header.start_pose;
  s.alpha = header.sensors.odometry ? header.sensors.odometry->alpha : std::array<double, 4>{};
  if (header.sensors.lidar) s.sigma_range_m = header.sensors.lidar->sigma_range_m;

  s.builder = std::make_unique<mrpt::slam::CMetricMapBuilderRBPF>(MakeMrptRbpfOptions(config_));
  s.builder->setMinLoggingLevel(mrpt::system::LVL_ERROR);
  s.builder->mapPDF.setMinLoggingLevel(mrpt::system::LVL_ERROR);
  s.builder->initialize();  // every particle at MRPT's origin = the stream's start pose
  std::deque<mrpt::math::TPose3D> path;
  s.builder->getCurrentMostLikelyPath(path);
  s.step_t_s.assign(path.size(), 0.0);  // the initial pose(s)
  s.step_odometry.assign(path.size(), SE2());
}

void MrptRbpfSlam::OnOdometry(const OdometryEvent& odometry) {
  state_->pending.Add(odometry, state_->alpha);
  state_->odometry = state_->odometry * odometry.delta;
}

void MrptRbpfSlam::OnLaserScan(const LaserScanEvent& scan) {
  State& s = *state_;
  mrpt::obs::CActionCollection actions;
  const mb::ActionNoiseFloor floor{};
  if (s.pending.empty) s.pending.t_s = scan.t_s;  // MRPT asserts an action: a zero motion
  mrpt::obs::CActionRobotMovement2D action = mb::ToMrptAction(s.pending, floor);
  mb::UseMrptGaussianModel(action, s.alpha, config_.motion_noise_scale, floor);
  actions.insert(action);
  s.pending.Reset();
  mrpt::obs::CSensoryFrame frame;
  std::shared_ptr<mrpt::obs::CObservation2DRangeScan> obs;
  if (config_.map == MrptRbpfMap::kPoints) {
    // A point map inserts and scores the scan's points, which have the same beam angles:
    // the plain scan, its cached point map built by MRPT (the map's insertion options).
    obs = std::make_shared<mrpt::obs::CObservation2DRangeScan>(mb::ToMrptScan(scan, s.sigma_range_m));
  } else {
    obs = std::make_shared<mrpt::obs::CObservation2DRangeScan>(
        mb::ToMrptScanForGrid(scan, s.sigma_range_m, config_.grid_beam_upsampling));
    // The likelihood field scores the scan's cached point map, built on first use with a
    // half-cell point spacing that drops most points of the sparse (upsampled) scan: build
    // it here with every valid beam.
    mrpt::maps::CPointsMap::TInsertionOptions points;
    points.minDistBetweenLaserPoints = 0.0f;
    points.isPlanarMap = true;
    obs->buildAuxPointsMap<mrpt::maps::CPointsMap>(&points);
  }
  frame.insert(obs);
  s.builder->processActionObservation(actions, frame);
  std::deque<mrpt::math::TPose3D> path;
  s.builder->getCurrentMostLikelyPath(path);
  if (path.size() > s.step_t_s.size()) {  // MRPT ran a filter step on this scan
    s.step_t_s.resize(path.size(), scan.t_s);
    s.step_odometry.resize(path.size(), s.odometry);
    s.estimate.diagnostics["neff"].push_back({scan.t_s, s.builder->mapPDF.ESS() * config_.particles});
  }
  s.scans.push_back({scan.t_s, s.odometry, s.step_t_s.size() - 1});
}

Estimate MrptRbpfSlam::Finish() {
  State& s = *state_;
  std::deque<mrpt::math::TPose3D> path;
  s.builder->getCurrentMostLikelyPath(path);
  std::vector<SE2> steps;  // the final most likely path at the filter steps, start frame
  for (size_t k = 0; k < path.size() && k < s.step_t_s.size(); ++k) steps.emplace_back(path[k].x, path[k].y, path[k].yaw);
  const auto add = [&](double t_s, const SE2& pose_start) {
    const PoseEstimate pe{t_s, mb::ToWorld(s.start, pose_start), Eigen::Matrix3d::Zero(), false};
    if (!s.estimate.trajectory.empty() && s.estimate.trajectory.back().t_s == pe.t_s)
      s.estimate.trajectory.back() = pe;  // a filter step on a scan at t = 0 refines the start
    else
      s.estimate.trajectory.push_back(pe);
  };
  if (!steps.empty()) {
    add(0.0, steps.front());
    for (const State::ScanRecord& r : s.scans) {
      const size_t k = std::min(r.step, steps.size() - 1);
      add(r.t_s, steps[k] * Between(s.step_odometry[k], r.odometry));  // exact at the filter steps
    }
  }
  const auto* maps = s.builder->getCurrentlyBuiltMetricMap();
  if (maps) {
    if (const auto grid = maps->mapByClass<mrpt::maps::COccupancyGridMap2D>()) {
      for (unsigned iy = 0; iy < grid->getSizeY(); ++iy)
        for (unsigned ix = 0; ix < grid->getSizeX(); ++ix)
          if (grid->getCell(static_cast<int>(ix), static_cast<int>(iy)) < config_.occupied_below_free_prob)
            s.estimate.map_points.push_back(s.start * Eigen::Vector2d(grid->idx2x(ix), grid->idx2y(iy)));
    }
    if (const auto points = maps->mapByClass<mrpt::maps::CSimplePointsMap>()) {
      for (size_t i = 0; i < points->size(); ++i) {
        float x = 0, y = 0;
        points->getPoint(i, x, y);
        s.estimate.map_points.push_back(s.start * Eigen::Vector2d(x, y));
      }
    }
  }
  return std::move(s.estimate);
}

ModuleInfo MrptRbpfSlamModule() {
  return MakeModuleInfo<MrptRbpfSlam, MrptRbpfSlamConfig>(
      "mrpt-rbpf-slam", "MRPT 2.5 CMetricMapBuilderRBPF: Rao-Blackwellized particle filter from LIDAR, a grid or point map per particle",
      {.odometry = true, .lidar = true}, &BindParams);
}

}  // namespace slambox
