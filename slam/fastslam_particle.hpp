#pragma once
// One FastSLAM particle and its measurement update: data association (known ids, or
// maximum likelihood against p0), the landmark EKFs, the importance weight and the
// existence counters (Thrun, Prob. Robotics, Tables 13.1-13.3; Montemerlo et al. 2002,
// 2003).
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <span>
#include <vector>

#include "core/stream.hpp"
#include "slam/detection_rate.hpp"
#include "slam/landmark_existence.hpp"
#include "slam/landmark_tree.hpp"
#include "slam/particle_path.hpp"

namespace slambox {

/// One scan's associations of one lineage, newest first and shared after resampling like
/// the path (particle_path.hpp), so each particle's assignments cost O(1) to copy.
struct AssignmentNode {
  int scan = 0;
  std::vector<int> landmark;  ///< per observation: the landmark key it updated or created, or -1
  std::vector<char> created;  ///< per observation: it created that landmark
  std::shared_ptr<AssignmentNode> parent;

  AssignmentNode(int s, std::vector<int> l, std::vector<char> c, std::shared_ptr<AssignmentNode> up)
      : scan(s), landmark(std::move(l)), created(std::move(c)), parent(std::move(up)) {}
  AssignmentNode(const AssignmentNode&) = delete;
  AssignmentNode& operator=(const AssignmentNode&) = delete;
  ~AssignmentNode() {  // iterative release, as PathNode's
    std::shared_ptr<AssignmentNode> next = std::move(parent);
    while (next && next.use_count() == 1) next = std::move(next->parent);
  }
};

/// The landmarks a lineage merged (place recognition), newest first, shared after
/// resampling like the path: `removed` became `kept`.
struct KeyMerge {
  int removed = 0, kept = 0;
  std::shared_ptr<const KeyMerge> parent;
};

/// A relaxation of the lineage's path (slam/fastslam_closure.hpp), newest first and shared
/// after resampling like the path: the path up to `t_s` since the heading variance was
/// `since_rad2` moves by the step errors that `lambda` (C^-1 dx) gives about `robot_xy`.
struct PathRelaxation {
  double t_s = 0, since_rad2 = 0;
  Eigen::Vector3d lambda = Eigen::Vector3d::Zero();
  Eigen::Vector2d robot_xy = Eigen::Vector2d::Zero();
  std::shared_ptr<const PathRelaxation> parent;
};

struct FastSlamParticle {
  SE2 pose;  ///< T_world_robot: a sample (1.0), or the motion-predicted mean since the last sample (2.0)
  /// FastSLAM 2.0: motion noise accumulated since the pose was last sampled (the prior of
  /// the proposal); always zero for 1.0.
  Eigen::Matrix3d pose_covariance = Eigen::Matrix3d::Zero();
  LandmarkTree map;
  int next_key = 0;             ///< key of the next new landmark (unknown association)
  double log_weight = 0.0;      ///< normalized since the last resampling
  double log_likelihood = 0.0;  ///< sum of all weight factors of this lineage (never reset)
  int origin = 0;               ///< index of its ancestor among the initial particles
  PathPtr path;
  std::shared_ptr<AssignmentNode> assignments;  ///< what this lineage did with each detection
  std::shared_ptr<const KeyMerge> merges;       ///< the landmarks this lineage merged
  std::shared_ptr<const PathRelaxation> relaxations;  ///< how this lineage's map moved since (its path follows at output)
  /// [m] the travel at which it last re-observed a landmark last seen a window before, and
  /// dead reckoning's summed heading variance [rad^2] then (slam/fastslam_closure.hpp: a
  /// closure ends a stretch of travel without such sightings; its path is tied to the old map
  /// where the stretch began)
  double old_seen_travel_m = 0.0, old_seen_heading_rad2 = 0.0;
  double closure_travel_m = -1.0;  ///< [m] the travel at which the last such stretch ended (-1: never)
  double closure_since_rad2 = 0.0; ///< [rad^2] the heading variance where that stretch began
};

struct ParticleUpdateOptions {
  Eigen::Matrix2d R = Eigen::Matrix2d::Identity();  ///< observation covariance (range, bearing)
  bool fastslam2 = false;
  /// Associate by the detector's ids (id < 0 is clutter and ignored); otherwise maximum
  /// likelihood with new landmarks against p0 and the existence counters.
  bool known_ids = true;
  /// p0, the likelihood of "a new landmark" (Thrun 13.2, w_{N+1}) in (range, bearing):
  /// with fake_density_per_m2 > 0, that density of detections no mapped landmark explains
  /// (clutter and landmarks not mapped yet) times the range, as dx dy = r dr dbearing;
  /// otherwise the constant exp(log_p0).
  double log_p0 = -5.0;
  double fake_density_per_m2 = 0.0;  ///< [1/m^2] see log_p0
  /// log p0 of a detection at this range.
  double LogP0(double range_m) const {
    return fake_density_per_m2 > 0.0 ? std::log(fake_density_per_m2 * std::max(range_m, std::sqrt(R(0, 0)))) : log_p0;
  }
  double range_max_m = 15.0;       ///< the detector's perceptual range
  double half_fov_rad = M_PI;      ///< half the detector's field of view
  double visibility_margin_m = 0.5;  ///< a landmark "should have been seen" only within range_max - margin
  double candidate_margin_m = 2.0;   ///< candidates for association: means within range_max + margin
  /// Existence counters: a miss in view costs P_D at the landmark's range from this rate
  /// (slam/detection_rate.hpp) when `estimate_detection_rate`, else 1.
  bool estimate_detection_rate = false;
  DetectionRate detection;
  double confirmed_counter = 10.0;  ///< landmarks whose counter reached this measure the rate
  /// [m] Counters: misses do not bring a confirmed landmark last seen more than this travel
  /// ago below confirmed_counter (FastSlamConfig::keep_confirmed; infinity: never).
  double keep_confirmed_unseen_m = std::numeric_limits<double>::infinity();
  /// Existence by Wald's sequential test instead of the counters: a sighting adds
  /// DetectedLogRatio, a miss in view MissedLogRatio, with P_D at the landmark's range (the
  /// estimated rate, or the stated one), P_G and the clutter mu of the pairing's own gate
  /// (where N(z; z_hat, L) >= p0); new landmarks start at `new_log_ratio`, are confirmed
  /// (reported, counted for the rate) at wald.log_confirm and removed at wald.log_delete.
  ExistenceRule existence = ExistenceRule::kCounts;
  /// Stamped on the landmarks seen or created (LandmarkGaussian): the robot's travel so far
  /// and dead reckoning's heading variance summed so far.
  double travel_m = 0.0;
  double heading_variance_rad2 = 0.0;
  /// Loop closure by re-observation (FastSlamConfig::closure_spread; slam/fastslam_closure.hpp):
  /// landmarks last seen more than `closure_old_after_m` of travel ago whose joint innovation
  /// fails the chi-square gate of `closure_gate_prob` move the pose, and the path since them
  /// relaxes (off: closure_old_after_m infinite). A relaxation (closure or constellation
  /// revisit) refuses a correction dx with dx^T C^-1 dx above `drift_gate_chi2`, chi2_3 at that
  /// probability (RelaxParticle).
  double closure_old_after_m = std::numeric_limits<double>::infinity();
  double closure_gate_prob = 0.99;
  double drift_gate_chi2 = 11.345;  ///< chi2_3(0.99); FastSlam::Start: chi2_3(constellation_gate_prob)
  std::span<const DriftSample> drift;  ///< at every odometry time so far, oldest first
  WaldThresholds wald;
  double new_log_ratio = 0.0;           ///< log prior odds of a new landmark (NewLandmarkPriorLogRatio)
  double clutter_density_per_m2 = 0.0;  ///< [1/m^2] clutter_per_scan over the footprint
  /// A landmark counted as confirmed (reported, measures the rate) under the rule in use.
  bool Confirmed(const LandmarkGaussian& lm) const {
    // Under the test the counter counts sightings (never decreased): confirmed by the test
    // and as many sightings as the counters need, so that a duplicate of a real landmark
    // (real detections, which the test calls real at once) is not reported after two.
    return lm.counter >= confirmed_counter && (existence == ExistenceRule::kCounts || lm.log_ratio >= wald.log_confirm);
  }
};

struct ParticleUpdateSummary {
  double log_weight_factor = 0.0;  ///< log p(z | particle) added to the weight
  int matched = 0;
  int created = 0;
  int discarded = 0;  ///< removed by the existence counters
  bool closure = false;  ///< the particle was corrected for a loop closure (slam/fastslam_closure.hpp)
  std::vector<int> landmark_of;  ///< per observation: the key it updated or created, or -1 (ignored)
  std::vector<char> creates;     ///< per observation: it created that landmark
  /// With estimate_detection_rate: confirmed landmarks (counter >= confirmed_counter)
  /// expected in view, (range, detected); empty otherwise.
  std::vector<std::pair<double, bool>> expected;
};

/// Processes one scan for one particle. `rng` draws FastSLAM 2.0's pose sample.
ParticleUpdateSummary UpdateParticle(FastSlamParticle& particle, const std::vector<LandmarkObservation>& scan,
                                     const ParticleUpdateOptions& options, std::mt19937_64& rng);

}  // namespace slambox
