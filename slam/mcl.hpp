#pragma once
// `mcl`: Monte Carlo localization in the known map (Thrun, Prob. Robotics, Table 8.2):
// particles move by sampling the odometry motion model (Table 5.6); each scan weights
// them by the likelihood-field range model (Table 6.3) on the scenario's walls; low-
// variance resampling when N_eff falls below a threshold. Output at every odometry event:
// the weighted mean and covariance of the cloud's main mode (the particles within 2 m of
// its heaviest 1 m cell, i.e. all of them while tracking). Tracking from the known start
// pose (init_sigma_* = 0) or from a Gaussian around it. With recovery on (Augmented MCL,
// Thrun Table 8.3), short- and long-term averages of the measurement likelihood decide
// how many particles are replaced by random free poses at resampling, so a kidnapped
// robot is found again.
#include <random>

#include "core/slam_module.hpp"
#include "slam/likelihood_field.hpp"

namespace slambox {

struct MclConfig {
  int particles = 500;
  /// [m] std of an endpoint's distance to the nearest wall: far above the range noise (1 cm)
  /// because neighbouring beams are not independent (Thrun 6.4); 0.2 m: ANEES 1.2-1.3 on loop, maze
  double sigma_hit_m = 0.2;
  double z_hit = 0.9;              ///< mixture weight of the hit term; the rest is uniform (z_rand)
  double max_distance_m = 1.0;     ///< [m] distance clamp of the likelihood field
  double grid_resolution_m = 0.05; ///< [m] likelihood-field cell
  int beam_step = 4;               ///< use every beam_step-th beam (neighbours are correlated)
  double neff_threshold = 0.5;     ///< [fraction of M] resample when N_eff < this * M
  double motion_noise_scale = 1.0; ///< factor on the odometry model's covariance
  double init_sigma_xy_m = 0.0;    ///< [m] initial spread around the start pose
  double init_sigma_theta_deg = 0.0;  ///< [deg]
  /// Augmented MCL: smoothing rates of the long- and short-term likelihood averages
  /// (0 < slow << fast; 0 = no random particles, plain MCL).
  double recovery_alpha_slow = 0.0;
  double recovery_alpha_fast = 0.0;
  double free_clearance_m = 0.2;  ///< [m] random particles are this far from every wall
};
void BindParams(MclConfig& c, ParamBinder& b);

class Mcl : public SlamModule {
 public:
  explicit Mcl(const MclConfig& config);
  void Start(const StreamHeader& header) override;
  void OnOdometry(const OdometryEvent& odometry) override;
  void OnLaserScan(const LaserScanEvent& scan) override;
  Estimate Finish() override;

 private:
  void Record(double t_s);
  SE2 RandomFreePose();

  MclConfig config_;
  DistanceGrid field_;
  std::array<double, 4> alpha_{};
  static constexpr int kBeamTableSize = 1024;  ///< intervals of the beam log-likelihood table
  std::vector<double> beam_log_likelihood_;    ///< at d = max_distance_m * k / kBeamTableSize
  std::mt19937_64 rng_;
  std::vector<SE2> poses_;
  std::vector<double> log_weights_;
  Eigen::Vector2d map_lo_, map_hi_;  ///< [m] bounds of the walls, for random particles
  double w_slow_ = 0.0, w_fast_ = 0.0;  ///< likelihood averages (per beam, geometric mean)
  Estimate estimate_;
};

ModuleInfo MclModule();

}  // namespace slambox
