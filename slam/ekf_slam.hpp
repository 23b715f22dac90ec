#pragma once
// `ekf-slam`: EKF-SLAM over robot pose and point landmarks (Thrun, Prob. Robotics,
// Ch. 10; Bailey et al. 2006). Odometry drives the prediction, each landmark scan is one
// batched Joseph-form update, unseen landmarks are added through the inverse observation
// model. Association by known ids, nearest neighbour with two gates, or JCBB. With
// unknown ids a landmark's existence is Wald's sequential test
// (slam/landmark_existence.hpp): every scan that predicts it in range and field of view
// is a trial of "real, detected with P_D (the rate the run measures at that range,
// slam/detection_rate.hpp) and then in its gate" against "clutter reappearing in its
// gate" (mu, the clutter the configured density puts in the gate). A new landmark is
// tentative until the test confirms it, deleted at Wald's lower bound or when it is out
// of view and not confirmed within `tentative_max_age_s` (`tentative_existence=sprt`, the
// default; `counts`: confirmed after `confirm_sightings`, deleted after
// `tentative_max_misses` misses in view or at `tentative_max_age_s`); a confirmed landmark
// is removed at the lower bound (`confirmed_existence=sprt`, the default; `counts`: +1
// seen, -P_D missed, removed at 0). Bounds: the gate's own error probability. Two
// landmarks that become statistically identical (slam/landmark_merge.hpp) are merged, the
// most similar pair first, unless they were ever seen in one scan (then they are two
// landmarks, however close). A pairing whose gate may hold clutter (the lone
// re-observation of an old landmark after drift) is held until
// pairings of other landmarks support it (slam/held_pairings.hpp). A loop closure that
// still rests on uncertain evidence (a released pairing or a merge whose own gate may hold
// a fake) is tested on the scans that follow it: the filter forks into a branch with the
// closure and one without, and Wald's test on their scan likelihoods
// (slam/scan_likelihood.hpp) keeps one (closure_test, slam/ekf_slam_closure.cpp). A revisit
// beyond every gate, mapped a second time, is recognized by its shape: the landmarks created
// in the last few footprints of travel matched as one rigid constellation onto those last
// seen before (constellation_merges, slam/ekf_slam_constellation.cpp). Optional
// FEJ-EKF (Huang, Mourikis & Roumeliotis 2008) or Invariant EKF (Barrau & Bonnabel 2015).
#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/slam_module.hpp"
#include "slam/constellation_match.hpp"
#include "slam/data_association.hpp"
#include "slam/detection_rate.hpp"
#include "slam/ekf_slam_filter.hpp"
#include "slam/held_pairings.hpp"
#include "slam/landmark_existence.hpp"

namespace slambox {

/// Data association: known ids if the sensor reports them, else JCBB (auto); known ids;
/// nearest neighbour; joint compatibility branch and bound.
enum class EkfAssociation { kAuto, kKnown, kNearestNeighbour, kJcbb };
/// auto, known, nn, jcbb.
const EnumNames<EkfAssociation>& EkfAssociationNames();

// ExistenceRule (slam/landmark_existence.hpp), for ekf-slam: counts are confirm_sightings /
// tentative_max_misses / tentative_max_age_s for tentative landmarks, the existence count
// for confirmed ones; chosen separately for tentative and confirmed landmarks.

struct EkfSlamConfig {
  EkfAssociation association = EkfAssociation::kAuto;
  double gate_accept_chi2 = 9.21;       ///< [chi2, 2 dof] accept the nearest landmark below this d^2
  double gate_new_chi2 = 25.0;          ///< [chi2, 2 dof] new landmark if every d^2 is above this
  double jcbb_joint_probability = 0.99; ///< [-] JCBB joint compatibility confidence
  int jcbb_max_nodes = 20000;           ///< [nodes] JCBB search budget per scan
  ExistenceRule tentative_existence = ExistenceRule::kSequentialTest;  ///< unknown ids: confirmation and deletion of tentative landmarks
  ExistenceRule confirmed_existence = ExistenceRule::kSequentialTest;  ///< unknown ids: removal of confirmed landmarks
  int confirm_sightings = 3;            ///< [scans] tentative_existence=counts: sightings that confirm a tentative landmark
  int tentative_max_misses = 3;         ///< [scans] tentative_existence=counts: misses in view that delete a tentative landmark
  double tentative_max_age_s = 2.0;     ///< [s] a tentative landmark not confirmed this long after its creation is deleted (sprt: while out of view)
  double visibility_margin_m = 0.5;     ///< [m] a landmark counts as missed only this far inside range_max
  double merge_probability = 0.99;      ///< [-] merge two landmarks whose difference d^2 is below this chi2 quantile (0 = never)
  bool hold_uncertain_pairings = true;  ///< unknown ids: hold a pairing whose gate may hold clutter until more evidence makes that unlikelier than a gate miss
  HoldEvidence hold_evidence = HoldEvidence::kLandmarksAndTracks;  ///< what that evidence is (slam/held_pairings.hpp)
  bool estimate_detection_rate = true;  ///< unknown ids: a miss in view costs P_D at its range (over the confirmed landmarks, slam/detection_rate.hpp) times the landmark's detections over those P_D predicted for it, at most 1 (else 1)
  int detection_rate_bands = 10;        ///< [bands] range bands of that estimate over [0, range_max)
  /// unknown ids: landmarks mapped within the last 2, 4 or 8 range_max of travel that form,
  /// under one rigid motion, the shape of landmarks last seen before it are merged into them,
  /// the robot moved with them (place recognition after drift, slam/ekf_slam_constellation.cpp)
  bool constellation_merges = true;
  int constellation_max_hypotheses = 100000;  ///< [hypotheses] constellation_merges: search budget per search (windows together)
  /// constellation_merges: old landmarks mapped during the drift (seen after the matched old
  /// ones) take their share of the match's motion (RevisitShares), not only the window's.
  /// Off by default: on 84 held-out random parks it made ekf-slam worse (ATE geomean 1.017,
  /// lm6_3 5.3 -> 26.5 m: a figure-eight whose crossing had already corrected what it moved)
  bool constellation_spread = false;
  bool closure_test = true;             ///< unknown ids: a loop closure on uncertain evidence forks the filter, Wald's test on the scans' likelihoods keeps one branch
  bool recover_heading = true;         ///< unknown ids: re-associate a scan that contradicts the predicted heading under a wider heading prior (slam/ekf_slam_recovery.cpp)
  bool fej = false;                     ///< first-estimates Jacobians (FEJ-EKF)
  bool invariant = false;               ///< right-invariant error (Invariant EKF, Barrau & Bonnabel 2015; slam/ekf_slam_filter.hpp)
  int update_iterations = 1;            ///< [-] iterated EKF update: relinearizations per scan (1 = EKF; slam/ekf_slam_filter.hpp)
  /// [-] an update whose robot step is improbable under the prior (beyond this chi2_3 quantile)
  /// is iterated, up to relinearize_iterations (0 = never; not with fej or invariant)
  double relinearize_step_prob = 0.99;
  int relinearize_iterations = 10;     ///< [-] Gauss-Newton steps of such an update
  double motion_noise_scale = 1.0;      ///< [-] factor on the odometry model's covariance
  double observation_noise_scale = 1.0; ///< [-] factor on the range-bearing covariance
};
void BindParams(EkfSlamConfig& c, ParamBinder& b);

/// Bookkeeping of one landmark in the state (same order as the state's landmarks).
struct LandmarkTrack {
  int key = 0;           ///< unique for the run, never reused (GraphSLAM's landmark handle)
  int id = -1;           ///< true id with known association, else -1
  int sightings = 0;
  double misses = 0;     ///< misses in view, each weighted by its detection rate (EkfSlam::ManageExistence)
  double existence = 1;  ///< +1 per sighting, -(its detection rate) per miss in view; a confirmed landmark is removed at 0
  bool confirmed = false;
  double created_t_s = 0.0;  ///< when it was created (tentative landmarks expire)
  Eigen::Vector2d first_estimate = Eigen::Vector2d::Zero();  ///< FEJ linearization point
  double expected_detections = 1;  ///< sum of P_D(range) over the scans it was predicted in view (its first: 1)
  double detected_scans = 1;       ///< ... of which it was detected in (its first included)
  double log_ratio = 0;  ///< existence=sprt: log odds real / phantom (prior at its birth + its scans in view)
  /// Its track continues (slam/held_pairings.hpp): since its creation, or since a pairing
  /// that placed it after its track had ended, the robot drifted less than one detection's
  /// gate from where it last placed the landmark (DriftedSincePlaced) and missed it in view
  /// no likelier than its gate misses a real detection (P_D by range); out of view it ends.
  bool tracked = true;
  double track_log_fake = 0;         ///< log P[the track's pairings held since its last used one were fakes] (TrackEvidence)
  double log_missed_since_seen = 0;  ///< log P[missed in the scans in view since its last sighting | real]
  Eigen::Matrix3d pose_covariance_when_placed = Eigen::Matrix3d::Zero();  ///< the robot's, after its creation or last pairing
  double created_travel_m = 0;  ///< [m] the robot's travel when it was created (constellation_merges)
  double seen_travel_m = 0;     ///< [m] ... when it was last detected
  double seen_heading_variance_rad2 = 0;  ///< [rad^2] the odometry's heading variance summed until then (heading_variance_rad2_)
};

class EkfSlam : public SlamModule {
 public:
  explicit EkfSlam(const EkfSlamConfig& config);
  void Start(const StreamHeader& header) override;
  void OnOdometry(const OdometryEvent& odometry) override;
  void OnLandmarks(const LandmarkEvent& event) override;
  Estimate Finish() override;

  /// Processes a scan and returns per observation the key of the landmark it updated or
  /// created, or -1 if it was discarded (clutter, ambiguous). With closure_test the keys are
  /// those of the branch that made the scan's closure; a test that ends in its rival renames
  /// them (revised_from_scan says from which scan on).
  std::vector<int> ProcessLandmarks(const LandmarkEvent& event);
  /// The first scan (index among the landmark events) whose keys the last ProcessLandmarks
  /// revised, or -1: a closure test ended in its rival, whose keys, poses and landmarks from
  /// its fork on replace this branch's (graphslam then rebuilds those scans' observations).
  int revised_from_scan() const { return revised_from_scan_; }
  /// The output so far: trajectory and assignments by scan, with the keys of the moment.
  const Estimate& partial_estimate() const { return estimate_; }
  const EkfSlamState& state() const { return state_; }
  /// While a loop closure is tested: the branch without it (else nullptr).
  const EkfSlam* closure_rival() const { return closure_rival_.empty() ? nullptr : &closure_rival_.front(); }
  const std::vector<LandmarkTrack>& tracks() const { return tracks_; }
  /// The key a landmark's observations now belong to: itself, or the landmark it was merged into.
  int ResolveKey(int key) const;
  /// Every key this filter has issued is below this one (merged-away and deleted keys too:
  /// ResolveKey still maps them, so a caller's own new keys must start here).
  int next_key() const { return next_key_; }
  /// [1/m^2] clutter plus new landmarks: the density of detections no mapped landmark explains.
  double FakeDensity() const;
  /// P[chi2(2) < gate_accept_chi2]: a real landmark's detection falls in its gate (after Start).
  double gate_probability() const { return gate_probability_; }

 private:
  /// Update, new landmarks, existence, merges and bookkeeping of a scan whose association is decided.
  std::vector<int> ApplyScan(const LandmarkEvent& event, const std::vector<Eigen::Vector2d>& z,
                             const std::vector<int>& target, const std::vector<bool>& held);
  std::vector<int> AssociateKnownIds(const std::vector<LandmarkObservation>& obs) const;
  /// Discards (holds) the pairings of `target` that may be fakes (slam/held_pairings.hpp); returns the held landmarks.
  std::vector<bool> HoldPairings(const std::vector<Eigen::Vector2d>& z, std::vector<int>& target);
  /// The landmark's track after a scan: paired (applied), held, or neither, with P_D at its
  /// predicted range if it was expected in view (else negative).
  void UpdateTrack(LandmarkTrack& t, bool paired, bool held, double p_detect_in_view) const;
  /// The robot's drift since landmark j was last placed, seen in its predicted detection,
  /// leaves one detection's gate in some direction.
  bool DriftedSincePlaced(int j) const;
  /// `mu`: per landmark the clutter expected in its gate at association time (sprt only).
  void ManageExistence(const std::vector<bool>& matched, const std::vector<bool>& held, const std::vector<double>& mu,
                       double t_s);
  /// Per landmark, the clutter expected in its individual gate (ExpectedFalseInGate).
  std::vector<double> ExpectedClutterInGates() const;
  /// A landmark predicted at zp = (range, bearing) is expected in view (visibility_margin_m inside range_max).
  bool ExpectedInView(const Eigen::Vector2d& zp) const {
    return zp.x() < range_max_m_ - config_.visibility_margin_m && std::abs(zp.y()) < half_fov_rad_;
  }
  double ExpectedConfirmedDetections() const;
  int PairedConfirmedLandmarks(const std::vector<int>& target) const;
  std::vector<int> RecoverHeading(const std::vector<Eigen::Vector2d>& z, const AssociationGates& gates,
                                  std::vector<int> target, double t_s);
  bool ReadyToConfirm(const LandmarkTrack& t) const;
  /// existence=sprt: log prior odds that a new landmark is real (births against clutter_per_scan).
  double NewLandmarkPriorLogRatio() const;
  /// certain_only: merges whose gate may hold a fake are left, and reported in *uncertain_found.
  int MergeDuplicates(bool certain_only = false, bool* uncertain_found = nullptr);
  /// Conditions the state on landmarks `keep` and `remove` being one and removes `remove`,
  /// its evidence joining `keep`'s (slam/landmark_merge.hpp); false if C is not positive definite.
  bool MergeTrackInto(int keep, int remove);
  /// constellation_merges (slam/ekf_slam_constellation.cpp): the landmarks mapped within the
  /// last 2, 4 or 8 range_max of travel matched as one shape onto those last seen before; returns the merges.
  int MergeConstellation(double t_s);

  // The closure test (slam/ekf_slam_closure.cpp). A pairing or a merge whose own gate
  // expects more fakes than the gate misses real landmarks (mu > 1 - P_G) closes a loop on
  // uncertain evidence. The filter then forks: this branch makes the closure, a copy (the
  // rival) does not (what only uncertain gates support becomes new landmarks). Both follow
  // the stream; each scan adds log p(scan | this) - log p(scan | rival)
  // (slam/scan_likelihood.hpp) to closure_log_ratio_, and at Wald's bounds (the existence
  // test's, +-log((1 - a) / a), a = 1 - P_G) the better branch goes on alone.
  bool MayStartClosureTest() const;
  bool UncertainGate(int landmark, double range_m) const;
  bool HasUncertainPairing(const std::vector<Eigen::Vector2d>& z, const std::vector<int>& target) const;
  void BlockUncertainClosures(const std::vector<Eigen::Vector2d>& z, std::vector<int>& target) const;
  void StartClosureTest(const LandmarkEvent& event, const std::vector<Eigen::Vector2d>& z,
                        const std::vector<int>& target, const std::vector<bool>& held);
  void StartClosureTestAtMerge(double t_s);
  void ContinueClosureTest(const LandmarkEvent& event);
  void EndClosureTest(bool keep_closure, double t_s);
  double ScanLogLikelihoodOf(const std::vector<Eigen::Vector2d>& z) const;
  /// [1/m^2] real births per scan over the sensor's footprint (Reid's density of new targets).
  double NewLandmarkDensity() const;
  bool SeenTogether(int key_a, int key_b) const { return co_observed_.count(std::minmax(key_a, key_b)) > 0; }
  void Record(double t_s, const std::string& name, double value) {
    estimate_.diagnostics[name].emplace_back(t_s, value);
  }

  EkfSlamConfig config_;
  std::array<double, 4> alpha_{};
  Eigen::Matrix2d R_ = Eigen::Matrix2d::Identity();
  double range_max_m_ = 1e9;
  double half_fov_rad_ = M_PI;
  double clutter_density_per_m2_ = 0.0;  ///< the sensor's clutter_per_scan over its footprint
  double gate_probability_ = 0.99;  ///< P[chi2(2) < gate_accept_chi2]: a real landmark's detection falls in its gate
  WaldThresholds wald_;  ///< existence=sprt: alpha = beta = the gate's miss probability 1 - gate_probability_
  bool known_ids_ = true;
  DetectionRate detection_;  ///< P_D by range, from the confirmed landmarks (unknown ids)
  EkfSlamState state_;
  std::vector<LandmarkTrack> tracks_;
  std::map<int, int> key_of_id_;  ///< true id -> key (known association)
  std::map<int, int> merged_into_;  ///< removed key -> key it was merged into
  std::set<std::pair<int, int>> co_observed_;  ///< (smaller, larger) keys seen in one scan
  HeldStreak held_streak_;  ///< pairings held in consecutive scans
  double clutter_per_scan_ = 0.0;  ///< the sensor's configured Poisson mean of false detections
  double births_ = 0;  ///< detections that started a new landmark (unknown ids)
  double first_scan_births_ = 0;  ///< of them, those of the first scan that had any (NewLandmarkDensity)
  int first_birth_scan_ = -1;     ///< that scan (-1: none yet)
  int next_key_ = 0;
  double travel_m_ = 0.0;  ///< [m] the odometry's path length so far
  double relinearize_gate_chi2_ = 0.0;  ///< chi2_3(relinearize_step_prob), 0 = off (Start)
  double heading_variance_rad2_ = 0.0;  ///< [rad^2] the motion model's heading variance summed over every odometry step so far
  std::deque<std::pair<double, SE2>> scan_path_;  ///< per landmark scan of the widest window: travel [m] and the pose after its update (constellation_merges)
  std::vector<int> constellation_searched_;  ///< keys of the recent landmarks of the last constellation search
  int scan_ = 0;  ///< landmark events processed (ObservationAssignment::scan)
  Eigen::Vector2d prior_position_ = Eigen::Vector2d::Zero();  ///< FEJ: position after the last prediction
  Estimate estimate_;
  std::vector<EkfSlam> closure_rival_;  ///< while a closure is tested: the branch without it (at most one)
  double closure_log_ratio_ = 0.0;      ///< the test's sum of log p(scan | this) - log p(scan | rival)
  double scan_log_likelihood_ = 0.0;    ///< this scan's, before its update (while testing)
  bool blocks_closures_ = false;        ///< the rival: no closure on uncertain pairings or merges
  bool uncertain_merge_pending_ = false;
  int fork_scan_ = -1;          ///< the running test's first scan whose keys the branches may differ in
  double test_fake_density_ = -1.0;  ///< [1/m^2] FakeDensity at the running test's fork, shared by both branches (-1: no test)
  int revised_from_scan_ = -1;  ///< revised_from_scan()
};

ModuleInfo EkfSlamModule();

}  // namespace slambox
