#pragma once
// `mrpt-rbpf-slam`: MRPT 2.5's CMetricMapBuilderRBPF with one occupancy grid per particle
// (grid-map RBPF from LIDAR and odometry, Grisetti/Stachniss style). Odometry between
// scans is one CActionRobotMovement2D; MRPT itself accumulates it until the robot has moved localize_lin_distance_m or
// localize_ang_distance_deg, then re-derives the step's noise with its own Gaussian model
// (stds from the stream's alphas, see UseMrptGaussianModel) and runs one particle-filter
// step. Scans go in upsampled (ToMrptScanForGrid) so MRPT's grid insertion and its
// likelihood field agree on beam angles. Proposal:
// "standard" = odometry sampling + likelihood-field weights (default), "optimal" =
// pfOptimalProposal with ICP against each particle's grid (MRPT's
// gridmapping_optimal_sampling setup; diverges with the upsampled scan, see README).
// The trajectory has a pose at every scan: the most likely particle's path at the filter
// steps (it changes as particles are resampled, so it is read at Finish), and between
// steps that path's last pose composed with the odometry since it; map_points are that
// particle's occupied grid cells.
#include <memory>
#include <string>

#include "core/slam_module.hpp"

namespace slambox {

/// MRPT's pfStandardProposal or pfOptimalProposal (scan matching).
enum class MrptProposal { kStandard, kOptimal };

struct MrptRbpfSlamConfig {
  MrptProposal proposal = MrptProposal::kStandard;  ///< standard | optimal
  int particles = 10;
  double resample_ess_ratio = 0.5;       ///< resample when ESS / N drops below this (MRPT BETA)
  double grid_resolution_m = 0.05;
  double localize_lin_distance_m = 0.2;  ///< motion between filter steps
  double localize_ang_distance_deg = 5.0;
  double insertion_lin_distance_m = 0.5; ///< motion between grid insertions
  double insertion_ang_distance_deg = 10.0;
  double likelihood_sigma_hit_m = 0.10;  ///< likelihood-field std (standard proposal)
  int likelihood_decimation = 5;         ///< use every n-th beam in the likelihood
  double icp_min_quality = 0.70;         ///< optimal proposal: below this, use odometry
  double motion_noise_scale = 1.0;       ///< MRPT Gaussian model stds: scale * sqrt(a_i) of the stream
  int grid_beam_upsampling = 16;         ///< see ToMrptScanForGrid: MRPT's grid insertion angle error / 16
  double occupied_below_free_prob = 0.3; ///< a cell is a map point when p(free) < this
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
