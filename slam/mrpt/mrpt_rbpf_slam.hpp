#pragma once
// `mrpt-rbpf-slam`: MRPT 2.5's CMetricMapBuilderRBPF, one map per particle: an occupancy
// grid (`map=grid`, default; grid-map RBPF from LIDAR and odometry, Grisetti/Stachniss
// style) or a point map (`map=points`, MRPT's gridmapping_RBPF_ICPbased_intel.ini).
// Odometry between scans is one CActionRobotMovement2D; MRPT itself accumulates it until
// the robot has moved localize_lin_distance_m or localize_ang_distance_deg, then
// re-derives the step's noise with its own Gaussian model (stds from the stream's alphas,
// see UseMrptGaussianModel) and runs one particle-filter step. With a grid, scans go in
// upsampled (ToMrptScanForGrid) so MRPT's grid insertion and its likelihood field agree
// on beam angles; a point map takes the plain scan (ToMrptScan), its insertion and its
// likelihood both use the points' angles. Proposal:
// "standard" = odometry sampling + map-likelihood weights (default), "optimal" =
// pfOptimalProposal: each particle's pose is drawn from the Gaussian of CICP's alignment
// of the scan against its own map (Grisetti et al. 2007's scan-matching approximation of
// p(x | x_prev, u, z, m)); weights then are the scan's likelihood at the drawn pose. With a
// grid this diverges (the upsampled scan, see README); with points it is MRPT's
// ICP-based RBPF.
// The trajectory has a pose at every scan: the most likely particle's path at the filter
// steps (it changes as particles are resampled, so it is read at Finish), and between
// steps that path's last pose composed with the odometry since it; map_points are that
// particle's occupied grid cells or its point map.
#include <memory>
#include <string>

#include "core/slam_module.hpp"
#include "slam/mrpt/mrpt_icp_params.hpp"

namespace slambox {

/// MRPT's pfStandardProposal or pfOptimalProposal (scan matching).
enum class MrptProposal { kStandard, kOptimal };
/// The map each particle carries: COccupancyGridMap2D or CSimplePointsMap.
enum class MrptRbpfMap { kGrid, kPoints };
/// MRPT's resampling schemes (the ini's resamplingMethod 0..3).
enum class MrptResampling { kMultinomial, kResidual, kStratified, kSystematic };

struct MrptRbpfSlamConfig {
  MrptProposal proposal = MrptProposal::kStandard;  ///< standard | optimal
  MrptRbpfMap map = MrptRbpfMap::kGrid;             ///< grid | points
  int particles = 10;
  MrptResampling resampling = MrptResampling::kSystematic;
  double resample_ess_ratio = 0.5;       ///< resample when ESS / N drops below this (MRPT BETA)
  double grid_resolution_m = 0.05;
  double localize_lin_distance_m = 0.2;  ///< motion between filter steps
  double localize_ang_distance_deg = 5.0;
  double insertion_lin_distance_m = 0.5; ///< motion between map insertions
  double insertion_ang_distance_deg = 10.0;
  double likelihood_sigma_hit_m = 0.10;  ///< likelihood-field std (standard proposal)
  int likelihood_decimation = 5;         ///< use every n-th beam in the likelihood
  double icp_min_quality = 0.70;         ///< optimal proposal: ICPGlobalAlign_MinQuality (2.5: a warning only)
  double motion_noise_scale = 1.0;       ///< MRPT Gaussian model stds: scale * sqrt(a_i) of the stream
  int grid_beam_upsampling = 16;         ///< see ToMrptScanForGrid: MRPT's grid insertion angle error / 16
  double occupied_below_free_prob = 0.3; ///< a cell is a map point when p(free) < this
  MrptIcpParams icp;                     ///< CICP of the optimal proposal (the `icp_*` keys; MRPT's defaults)
  // The point map (map=points; defaults are MRPT's CPointsMap options).
  double points_min_distance_m = 0.02;   ///< insertion: drop points closer than this to the last
  double points_likelihood_var_m2 = 0.0025;   ///< MRPT sigma_dist (a variance): log p = -mean(min(d², max_corr²)) / var
  double points_likelihood_max_corr_m = 1.0;  ///< distances clipped here (a floor on a point's likelihood)
  int points_likelihood_decimation = 10;      ///< score every n-th scan point
};
void BindParams(MrptRbpfSlamConfig& c, ParamBinder& b);

class MrptRbpfSlam : public SlamModule {
 public:
  explicit MrptRbpfSlam(const MrptRbpfSlamConfig& config);
  ~MrptRbpfSlam() override;
  void Start(const StreamHeader& header) override;
  void OnOdometry(const OdometryEvent& odometry) override;
  void OnLaserScan(const LaserScanEvent& scan) override;
  Estimate Finish() override;

  struct State;  ///< MRPT objects (pimpl: MRPT stays out of this header)

 private:
  MrptRbpfSlamConfig config_;
  std::unique_ptr<State> state_;
};

ModuleInfo MrptRbpfSlamModule();

}  // namespace slambox
