#pragma once
// `fastslam1` and `fastslam2`: Rao-Blackwellized particle filters for landmark SLAM
// (Montemerlo et al. 2002, 2003; Thrun, Prob. Robotics, Ch. 13). M particles, each a
// pose (and its history) with its own map of 2x2 landmark EKFs in a copy-on-write tree
// shared between particles (slam/landmark_tree.hpp).
//
// Output: Estimate::trajectory is the path of the particle with the largest weight at the
// end (its ancestry's poses at every odometry event; ties on the weight are broken by
// the lineage's total likelihood), moved as its lineage's map moved at each loop closure
// and revisit (RelaxedPath, slam/fastslam_closure.hpp: the particle's path is smoothed
// as a pose graph would be, within dead reckoning's drift model), with, at each time, the covariance of the weighted
// particle cloud (plus the mean of the 2.0 proposal priors) around the weighted mean,
// for NEES, only after the time where all final particles' paths coalesce (before it the
// set holds one path and no covariance is reported; diagnostic coalesced_until_s).
// `trajectory = mean` outputs the filtered weighted mean pose instead,
// `path_mean` the weighted mean of the final particles' ancestral paths (neither relaxed). Landmarks are
// the best particle's map. Diagnostics per landmark scan: neff (before resampling),
// distinct_ancestors (initial particles with living descendants), resampled (0/1),
// landmarks (best particle's map size); map_tree_nodes (distinct live tree nodes of all
// particles, before resampling) at each particle snapshot; constellation_merges (the best
// particle's merges) and constellation_chance (the match's union bound) at each accepted
// revisit (slam/fastslam_constellation.cpp); closure_particles (particles corrected) at each
// scan with a loop closure by re-observation (known ids, slam/fastslam_closure.hpp).
#include <array>
#include <deque>
#include <random>
#include <string>
#include <vector>

#include "core/slam_module.hpp"
#include "slam/fastslam_particle.hpp"

namespace slambox {

/// Estimate::trajectory: the best particle's path, the filtered weighted mean pose, or the
/// weighted mean of the final particles' ancestral paths.
enum class FastSlamTrajectory { kBest, kMean, kPathMean };

/// Where p0, the likelihood of "a new landmark", comes from (FastSlamConfig::new_landmark_p0).
enum class NewLandmarkP0 { kDensity, kGate };
/// When a miss costs the estimated detection rate (FastSlamConfig::estimate_detection_rate):
/// kAuto where the stream does not state its P_D (LandmarkSensorConfig::detection_prob_known
/// false: converted logs), kAlways, kNever. Names "auto", "true", "false".
enum class DetectionRateUse { kAuto, kAlways, kNever };
/// How landmarks are confirmed and removed with unknown ids (FastSlamConfig::existence):
/// kAuto as DetectionRateUse::kAuto (the test where the stream does not state its P_D),
/// else the counters or the sequential test (ExistenceRule). Names "auto", "counts", "sprt".
enum class FastSlamExistence { kAuto, kCounts, kSequentialTest };

struct FastSlamConfig {
  int particles = 100;  ///< M
  /// Added to the stream's seed to seed this module's generator: 0 draws as every run of the
  /// stream does; others draw the same filter's particles anew (a recorded stream's seed is
  /// fixed, and a particle filter's error on one draw says little: slam/README_fastslam.md).
  int seed_offset = 0;
  /// An observation starts a new landmark when every landmark's likelihood is below p0.
  /// kDensity: p0 is the density, in (range, bearing), of detections no mapped landmark
  /// explains: (clutter_per_scan over the detector's footprint + landmarks not mapped yet,
  /// estimated from the births so far) times the range (FakeDetectionDensity below).
  /// kGate: the density N(nu; 0, R) of an innovation at the squared Mahalanobis distance
  /// new_landmark_gate_chi2 under the sensor noise R alone:
  /// log p0 = -log(2 pi) - log det(R)/2 - gate/2.
  NewLandmarkP0 new_landmark_p0 = NewLandmarkP0::kGate;
  double new_landmark_gate_chi2 = 25.0;  ///< [chi2] p0 with new_landmark_p0 = gate
  double neff_threshold = 0.5;    ///< [fraction of M] resample when N_eff < neff_threshold * M
  bool use_known_ids = true;      ///< associate by the detector's ids when the stream has them
  double visibility_margin_m = 0.5;  ///< [m] counters: "should have been seen" within range_max - margin
  double candidate_margin_m = 2.0;   ///< [m] association candidates: means within range_max + margin
  int report_min_counter = 10;       ///< unknown ids: report landmarks whose counter reached this (10 Hz: ~1 s net sightings)
  /// Unknown ids, existence by the counters: misses do not bring a reported landmark that was
  /// last seen before the revisit search's widest window (RevisitWidestWindow: 8 range_max of
  /// travel) below report_min_counter, so it stays mapped. Whether it should have been seen
  /// rests on a pose that has drifted since; deleting it erases the old map a revisit must be
  /// matched against (constellation_merges; slam/README_fastslam.md). Landmarks seen within
  /// the window (a duplicate, a confirmed phantom) are deleted by their misses as before.
  bool keep_confirmed = true;
  double motion_noise_scale = 1.0;   ///< factor on the odometry model's covariance
  /// Unknown ids: a miss in view costs the counter P_D at the landmark's range, estimated
  /// per range band from the best particle's landmarks whose counter reached
  /// report_min_counter, the sensor's detection_prob as prior (slam/detection_rate.hpp);
  /// else 1 (Thrun's counter). auto: only where the stream does not state its P_D; a
  /// stated one is trusted (in simulation the rate costs: slam/README_fastslam.md).
  DetectionRateUse estimate_detection_rate = DetectionRateUse::kAuto;
  int detection_rate_bands = 10;     ///< [bands] range bands of that estimate over [0, range_max)
  /// Unknown ids: the existence of a landmark by the counters above (Thrun 13.2) or by
  /// Wald's sequential test of "real" against "clutter in its gate", as ekf-slam's
  /// (ParticleUpdateOptions::existence); the test confirms and deletes at the error
  /// probabilities existence_error_prob (alpha = beta). auto: the test where the stream
  /// does not state its P_D (converted logs: measured in slam/README_fastslam.md), the
  /// counters where it does (the simulator: the test costs there, same section).
  FastSlamExistence existence = FastSlamExistence::kAuto;
  double existence_error_prob = 0.01;
  /// Unknown ids: a revisit mapped a second time is recognized by its shape, as ekf-slam's
  /// (slam/constellation_revisit.hpp), in the best particle's map; every particle holding the
  /// matched pairs then moves its pose and the landmarks it saw within the window by its own
  /// fit of the pairs and merges each pair (slam/fastslam_constellation.cpp).
  bool constellation_merges = true;
  int constellation_max_hypotheses = 100000;  ///< [hypotheses] constellation_merges: search budget per search
  /// constellation_merges: the heading gate's probability (1 - it: the false-match probability);
  /// the tolerance is the 2-dof gate at it (RevisitTolerance).
  double constellation_gate_prob = 0.99;
  /// constellation_merges: the particle's path since the matched old ones relaxes under its
  /// motion, and the landmarks seen since move with it (RelaxParticle, slam/fastslam_closure.hpp)
  bool constellation_spread = true;
  /// Loop closure by re-observation (slam/fastslam_closure.hpp; known ids): a particle whose landmarks
  /// last seen beyond the revisit search's widest window come back with an innovation its pose
  /// prior cannot explain (chi-square at constellation_gate_prob) moves its pose by the drift
  /// that explains them, and the map it drew since them by its share (RevisitShare).
  bool closure_spread = true;
  double snapshot_period_s = 10.0;   ///< [s] particle snapshots for figures (0 = none)
  FastSlamTrajectory trajectory = FastSlamTrajectory::kBest;  ///< what goes into Estimate::trajectory
};
void BindParams(FastSlamConfig& c, ParamBinder& b);

/// FastSLAM 2.0 defaults: as FastSlamConfig but with 50 particles.
struct FastSlam2Config : FastSlamConfig {
  FastSlam2Config() { particles = 50; }
};
void BindParams(FastSlam2Config& c, ParamBinder& b);

/// [1/m^2] Detections per scan and m^2 that no mapped landmark explains, after
/// `scans_done` scans over a detector footprint of `footprint_m2` (r_max^2 half_fov): the
/// clutter, clutter_per_scan / footprint, plus the landmarks not mapped yet
/// (UnmappedLandmarkDensity, slam/landmark_existence.hpp, of the `births` so far, mean over
/// the particles, with one pseudo-scan of one birth before the first scan).
double FakeDetectionDensity(double clutter_per_scan, double births, int scans_done, double footprint_m2);

class FastSlam : public SlamModule {
 public:
  FastSlam(const FastSlamConfig& config, bool fastslam2);
  void Start(const StreamHeader& header) override;
  void OnOdometry(const OdometryEvent& odometry) override;
  void OnLandmarks(const LandmarkEvent& landmarks) override;
  Estimate Finish() override;

  const std::vector<FastSlamParticle>& particles() const { return particles_; }
  /// Distinct live landmark-tree nodes over all particles (memory, in nodes).
  size_t MapTreeNodes() const;

 private:
  void RecordCloud(double t_s);
  void Diagnose(double t_s, const std::string& name, double value) { estimate_.diagnostics[name].emplace_back(t_s, value); }
  int BestParticle() const;
  /// Time of the newest pose node that every particle's path shares (-1: none).
  double CoalescedUntil() const;
  std::vector<PoseEstimate> PathMean() const;
  /// constellation_merges (slam/fastslam_constellation.cpp): returns the merges of the best particle.
  int MergeConstellation(double t_s);

  FastSlamConfig config_;
  bool fastslam2_;
  std::string name_;
  std::array<double, 4> alpha_{};
  ParticleUpdateOptions update_;
  std::mt19937_64 rng_;
  std::vector<FastSlamParticle> particles_;
  std::vector<PoseEstimate> cloud_;  ///< weighted mean and covariance, at each path time
  double next_snapshot_s_ = 0.0;
  int scan_ = 0;  ///< landmark events processed (ObservationAssignment::scan)
  double clutter_per_scan_ = 0.0;  ///< the detector's (stream header)
  double births_ = 0.0;            ///< landmarks created so far, mean over the particles
  double travel_m_ = 0.0;               ///< [m] the odometry's travel so far (constellation_merges)
  double heading_variance_rad2_ = 0.0;  ///< [rad^2] the motion model's heading variance summed over every step so far
  std::vector<DriftSample> drift_;      ///< the variances summed by each odometry time (path relaxation)
  std::deque<std::pair<double, double>> scan_travel_;  ///< per landmark scan of the widest window: travel [m], time [s]
  std::vector<int> constellation_searched_;  ///< keys of the recent landmarks of the last constellation search
  Estimate estimate_;
};

struct FastSlam1 : FastSlam {
  explicit FastSlam1(const FastSlamConfig& c) : FastSlam(c, false) {}
};
struct FastSlam2 : FastSlam {
  explicit FastSlam2(const FastSlam2Config& c) : FastSlam(c, true) {}
};

ModuleInfo FastSlam1Module();
ModuleInfo FastSlam2Module();

}  // namespace slambox
