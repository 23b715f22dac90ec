#include "slam/ekf_slam.hpp"

#include <cmath>

#include "core/chi_square.hpp"
#include "core/error.hpp"
#include "core/odometry_model.hpp"
#include "slam/range_bearing.hpp"

namespace slambox {

const EnumNames<EkfAssociation>& EkfAssociationNames() {
  static const EnumNames<EkfAssociation> names = {{EkfAssociation::kAuto, "auto"},
                                                  {EkfAssociation::kKnown, "known"},
                                                  {EkfAssociation::kNearestNeighbour, "nn"},
                                                  {EkfAssociation::kJcbb, "jcbb"}};
  return names;
}

void BindParams(EkfSlamConfig& c, ParamBinder& b) {
  b.Bind("association", c.association, EkfAssociationNames(),
         "data association: auto (known ids if the sensor has them, else jcbb), known, nn, jcbb");
  b.Bind("gate_accept_chi2", c.gate_accept_chi2, "chi2", "accept the nearest landmark if its d^2 is below", Above(0));
  b.Bind("gate_new_chi2", c.gate_new_chi2, "chi2", "new landmark if every d^2 is above (ambiguous in between)",
         Above(0));
  b.Bind("jcbb_joint_probability", c.jcbb_joint_probability, "-", "JCBB joint compatibility confidence",
         Range{.min = 0, .max = 1, .min_open = true, .max_open = true});
  b.Bind("jcbb_max_nodes", c.jcbb_max_nodes, "nodes", "JCBB search budget per scan", AtLeast(1));
  b.Bind("tentative_existence", c.tentative_existence, ExistenceRuleNames(),
         "unknown ids, tentative landmarks: sprt (Wald's test, each scan in view a trial of 'real: detected with the "
         "measured P_D(range), then in its gate with P[chi2(2) < gate_accept_chi2]' against 'clutter in its gate: "
         "1 - exp(-mu)', mu from clutter_per_scan and the gate's area; prior odds from the births against "
         "clutter_per_scan; confirmed at log((1-b)/a), deleted at log(b/(1-a)), a = b = the gate's miss probability) "
         "or counts (confirm_sightings, tentative_max_misses, tentative_max_age_s)");
  b.Bind("confirmed_existence", c.confirmed_existence, ExistenceRuleNames(),
         "unknown ids, confirmed landmarks: sprt (that test continued from the landmark's birth, removed at "
         "log(b/(1-a))) or counts (+1 per sighting, -P_D per miss, removed at 0)");
  b.Bind("confirm_sightings", c.confirm_sightings, "scans", "tentative_existence=counts: sightings that confirm a tentative landmark",
         AtLeast(1));
  b.Bind("tentative_max_misses", c.tentative_max_misses, "scans",
         "tentative_existence=counts: misses in view that delete a tentative landmark", AtLeast(1));
  b.Bind("tentative_max_age_s", c.tentative_max_age_s, "s",
         "a tentative landmark not confirmed this long after its creation is deleted (tentative_existence=sprt: only while out of view)", Above(0));
  b.Bind("visibility_margin_m", c.visibility_margin_m, "m", "a landmark is expected in view this far inside range_max",
         AtLeast(0));
  b.Bind("merge_probability", c.merge_probability, "-",
         "merge two landmarks whose difference d^2 is below this chi2(2) quantile, unless seen in one scan (0 = never)",
         Range{.min = 0, .max = 1, .max_open = true});
  b.Bind("constellation_merges", c.constellation_merges, "-",
         "unknown ids: when a landmark is confirmed, the confirmed landmarks created within the last 2, 4, then 8 "
         "range_max of travel are matched as one rigid shape onto those last seen before (pairs of equal length seed "
         "the motions; tolerance sqrt(2 gate_accept_chi2) times a detection's largest standard deviation at "
         "range_max). A match whose chance under the old landmarks' density (union bound over the motions tried) is "
         "below the gate's miss probability, with no other match pairing them differently, moves the robot and the "
         "landmarks seen within the window by its motion (with the fit's uncertainty) and merges its pairs "
         "(slam/ekf_slam_constellation.cpp; graphslam's front end: off, its smoother re-decides association)");
  b.Bind("constellation_max_hypotheses", c.constellation_max_hypotheses, "hypotheses",
         "constellation_merges: search budget; windows whose pairs of equal length make more motions than this "
         "(the earlier windows' included) are not searched (Victoria Park, 79 m range: millions)", AtLeast(0));
  b.Bind("constellation_spread", c.constellation_spread, "-",
         "constellation_merges: old landmarks last seen after the matched old ones (mapped during the drift) move by "
         "the part of the match's motion dead reckoning's heading variance accrued until their sighting, "
         "(v - v_matched) / (v_now - v_matched), along the motion's screw (pose-graph relaxation's spread of a loop's "
         "error); off (the default; slam/README_landmark_slam.md: worse on held-out parks): only the robot and the "
         "window's landmarks move");
  b.Bind("hold_uncertain_pairings", c.hold_uncertain_pairings, "-",
         "unknown ids: hold a pairing whose gate (given the scan's other pairings) expects more clutter than the gate's "
         "miss probability, until held pairings in consecutive scans (hold_evidence) make a fake unlikelier than that");
  b.Bind("hold_evidence", c.hold_evidence, HoldEvidenceNames(),
         "what lets a held pairing through: landmarks (the product of mu over the distinct landmarks held in "
         "consecutive scans; a repeat of one landmark is no evidence, an unmapped tree stays in its gate) or scans "
         "(mu over consecutive scans repeating the pairing: independent only for clutter) or tracks (landmarks, and "
         "the repeats a landmark's continuing track held since its last used pairing: since it was placed the robot "
         "drifted less than one detection's gate and missed it no likelier than its gate misses)");
  b.Bind("estimate_detection_rate", c.estimate_detection_rate, "-",
         "unknown ids: a miss in view costs the detection probability at its range (estimated from the confirmed "
         "landmarks, the sensor's detection_prob as prior) times the landmark's detections over those predicted for "
         "it (at most 1), not 1");
  b.Bind("detection_rate_bands", c.detection_rate_bands, "bands", "range bands of the detection probability estimate",
         AtLeast(1));
  b.Bind("closure_test", c.closure_test, "-",
         "unknown ids: a pairing or merge whose own gate may hold a fake (clutter or an unmapped landmark; mu > 1 - P_G) forks the "
         "filter into a branch with that loop closure and one without (uncertain gates there start new landmarks); "
         "each later scan adds log p(scan | branch), the Poisson likelihood of its detections (clutter_per_scan and "
         "the measured birth density, P_D(range) and existence of the landmarks, their expected detections in view), "
         "and the branch ahead by log((1-a)/a), a = 1 - P[chi2(2) < gate_accept_chi2], goes on alone (graphslam: its "
         "graph takes the surviving branch's association of those scans)");
  b.Bind("recover_heading", c.recover_heading, "-",
         "unknown ids: a scan pairing no confirmed landmark where the map expects lambda detections in view "
         "(exp(-lambda) below the gate's miss probability) contradicts the predicted heading: its association is "
         "searched again with the heading's standard deviation widened 2, 4, 8, 16 times, the first pairing two or "
         "more confirmed landmarks kept with that variance (slam/ekf_slam_recovery.cpp)");
  b.Bind("fej", c.fej, "-", "first-estimates Jacobians (FEJ-EKF, Huang et al. 2008)");
  b.Bind("invariant", c.invariant, "-",
         "right-invariant error (Invariant EKF, Barrau & Bonnabel 2015): each update's correction is a motion of "
         "robot and map on SE_{1+n}(2) and the covariance follows it, so rotating or translating everything stays "
         "unobservable (not with fej=true or update_iterations > 1: those linearize the standard error)");
  b.Bind("update_iterations", c.update_iterations, "-",
         "iterated EKF: Gauss-Newton steps of each scan's update, relinearized at the iterate (1 = plain EKF)", AtLeast(1));
  b.Bind("relinearize_step_prob", c.relinearize_step_prob, "-",
         "a scan's update whose EKF step moves the robot improbably far under the prior (squared Mahalanobis "
         "length beyond this chi2 quantile, 3 dof) is iterated as with update_iterations: the linearization at the "
         "prior cannot carry a correction of many sigmas (e.g. a landmark re-sighted after a long drift); 0 = never "
         "(not with fej=true or invariant=true, which keep their own linearization)");
  b.Bind("relinearize_iterations", c.relinearize_iterations, "-",
         "Gauss-Newton steps of an update iterated by relinearize_step_prob", AtLeast(1));
  b.Bind("motion_noise_scale", c.motion_noise_scale, "-", "factor on the odometry model's covariance", Above(0));
  b.Bind("observation_noise_scale", c.observation_noise_scale, "-", "factor on the range-bearing covariance", Above(0));
}

EkfSlam::EkfSlam(const EkfSlamConfig& config) : config_(config) {
  // ekf-slam's own settings, and graphslam's front end (same field names).
  auto fail = [](const std::string& field, const std::string& problem, const std::string& fix) {
    throw InputError("--set algo.ekf-slam." + field + " (or algo.graphslam." + field + ")", 0, problem, fix);
  };
  if (!(config.merge_probability >= 0 && config.merge_probability < 1))
    fail("merge_probability", "must lie in [0, 1)", "e.g. 0.99, or 0 to never merge");
  if (!(config.tentative_max_age_s > 0)) fail("tentative_max_age_s", "must be positive", "e.g. 2");
  if (!(config.relinearize_step_prob >= 0 && config.relinearize_step_prob < 1))
    fail("relinearize_step_prob", "must lie in [0, 1)", "e.g. 0.99, or 0 to never relinearize");
  if (config.fej && config.update_iterations > 1)
    fail("update_iterations", "cannot relinearize with first-estimates Jacobians (fej=true)", "set fej=false or update_iterations=1");
}

void EkfSlam::Start(const StreamHeader& header) {
  alpha_ = header.sensors.odometry ? header.sensors.odometry->alpha : std::array<double, 4>{};
  const LandmarkSensorConfig sensor = header.sensors.landmarks.value_or(LandmarkSensorConfig{});
  R_ = config_.observation_noise_scale * ObservationCovariance(sensor);
  relinearize_gate_chi2_ = config_.relinearize_step_prob > 0 ? ChiSquareQuantile(config_.relinearize_step_prob, 3.0) : 0.0;
  range_max_m_ = sensor.range_max_m;
  half_fov_rad_ = sensor.fov_deg * M_PI / 360.0;
  // The footprint is the circular sector of radius range_max and angle fov: r^2 * half_fov.
  clutter_density_per_m2_ = sensor.clutter_per_scan / (range_max_m_ * range_max_m_ * half_fov_rad_);
  known_ids_ = config_.association == EkfAssociation::kKnown ||
               (config_.association == EkfAssociation::kAuto && sensor.known_ids);
  gate_probability_ = ChiSquareCdf(config_.gate_accept_chi2, 2.0);
  const double gate_miss = std::clamp(1.0 - gate_probability_, 1e-12, 0.49);
  wald_ = MakeWaldThresholds(gate_miss, gate_miss);
  detection_ = MakeDetectionRate(range_max_m_, config_.detection_rate_bands, sensor.detection_prob);
  state_ = MakeInitialState(header.start_pose);
  tracks_.clear();
  key_of_id_.clear();
  merged_into_.clear();
  co_observed_.clear();
  held_streak_.clear();
  closure_rival_.clear();
  closure_log_ratio_ = 0.0;
  scan_log_likelihood_ = 0.0;
  blocks_closures_ = false;
  uncertain_merge_pending_ = false;
  fork_scan_ = revised_from_scan_ = -1;
  test_fake_density_ = -1.0;
  clutter_per_scan_ = sensor.clutter_per_scan;
  births_ = first_scan_births_ = 0;
  first_birth_scan_ = -1;
  next_key_ = 0;
  travel_m_ = 0.0;
  heading_variance_rad2_ = 0.0;
  constellation_searched_.clear();
  scan_path_.clear();
  scan_ = 0;
  prior_position_ = header.start_pose.translation();
  estimate_ = Estimate{};
  estimate_.trajectory.push_back({0.0, header.start_pose, Eigen::Matrix3d::Zero(), true});
}

void EkfSlam::OnOdometry(const OdometryEvent& odometry) {
  if (!closure_rival_.empty()) closure_rival_.front().OnOdometry(odometry);
  const OdometryIncrement u = Decompose(odometry.delta);
  const MotionPrediction p = PredictMotion(state_.Pose(), u);
  Eigen::Matrix3d J = p.J_pose_pose;
  if (config_.fej) {  // Huang et al. 2008, eq. 27: the displacement between the first estimates
    const Eigen::Vector2d d = p.pose.translation() - prior_position_;
    J(0, 2) = -d.y();
    J(1, 2) = d.x();
  }
  const Eigen::Matrix3d M = config_.motion_noise_scale * IncrementCovariance(u, alpha_);
  travel_m_ += std::abs(u.trans);
  heading_variance_rad2_ += M(0, 0) + M(2, 2);  // rot1 and rot2 turn the heading
  PredictState(state_, p.pose, J, p.J_pose_increment * M * p.J_pose_increment.transpose());
  prior_position_ = p.pose.translation();
  estimate_.trajectory.push_back({odometry.t_s, state_.Pose(), state_.covariance.topLeftCorner<3, 3>(), true});
}

std::vector<int> EkfSlam::AssociateKnownIds(const std::vector<LandmarkObservation>& obs) const {
  std::vector<int> target(obs.size(), Association::kDiscard);
  for (size_t i = 0; i < obs.size(); ++i) {
    if (obs[i].id < 0) continue;  // clutter: a detector that knows ids reports it as -1
    const auto it = key_of_id_.find(obs[i].id);
    if (it == key_of_id_.end()) {
      target[i] = Association::kNew;
      continue;
    }
    for (size_t j = 0; j < tracks_.size(); ++j)
      if (tracks_[j].key == it->second) target[i] = static_cast<int>(j);
  }
  // The same id twice in one scan: keep the first.
  for (size_t i = 0; i < obs.size(); ++i)
    for (size_t k = 0; k < i; ++k)
      if (obs[i].id >= 0 && obs[k].id == obs[i].id) target[i] = Association::kDiscard;
  return target;
}

std::vector<int> EkfSlam::ProcessLandmarks(const LandmarkEvent& event) {
  revised_from_scan_ = -1;
  const auto& obs = event.observations;
  std::vector<Eigen::Vector2d> z(obs.size());
  for (size_t i = 0; i < obs.size(); ++i) z[i] = {obs[i].range_m, obs[i].bearing_rad};
  const AssociationGates gates{config_.gate_accept_chi2, config_.gate_new_chi2, config_.jcbb_joint_probability,
                               config_.jcbb_max_nodes};
  std::vector<int> target;
  if (known_ids_) target = AssociateKnownIds(obs);
  else if (config_.association == EkfAssociation::kNearestNeighbour) target = AssociateNearestNeighbour(state_, z, R_, gates).landmark;
  else {
    target = AssociateJcbb(state_, z, R_, gates).landmark;
    if (config_.recover_heading) target = RecoverHeading(z, gates, std::move(target), event.t_s);
  }
  const std::vector<bool> held = HoldPairings(z, target);
  if (blocks_closures_) BlockUncertainClosures(z, target);
  const bool testing = !closure_rival_.empty();
  if (testing || blocks_closures_) scan_log_likelihood_ = ScanLogLikelihoodOf(z);  // before the update
  if (MayStartClosureTest() && HasUncertainPairing(z, target)) StartClosureTest(event, z, target, held);
  const std::vector<int> keys = ApplyScan(event, z, target, held);
  if (uncertain_merge_pending_) StartClosureTestAtMerge(event.t_s);
  if (testing) ContinueClosureTest(event);
  return keys;
}

std::vector<int> EkfSlam::ApplyScan(const LandmarkEvent& event, const std::vector<Eigen::Vector2d>& z,
                                    const std::vector<int>& target, const std::vector<bool>& held) {
  const auto& obs = event.observations;
  const std::vector<double> mu = ExpectedClutterInGates();  // the gates the pairings were made in

  // One batched update with every matched observation: iterated (always, or where the EKF
  // step is improbable under the prior), which linearizes itself; else linearized here at the
  // current estimate, or for FEJ at the robot's prior and the landmark's first estimate.
  const bool iterate_all = config_.update_iterations > 1;
  const bool gated = !iterate_all && relinearize_gate_chi2_ > 0 && !config_.fej && !config_.invariant;
  std::vector<int> keys(obs.size(), -1);
  std::vector<LinearizedObservation> lin;
  std::vector<LandmarkMeasurement> measured;  // for the iterated update
  std::vector<bool> matched(tracks_.size(), false);
  const SE2 pose = state_.Pose();
  for (size_t i = 0; i < obs.size(); ++i) {
    const int j = target[i];
    if (j < 0) continue;
    if (iterate_all || gated) {
      measured.push_back({j, z[i]});
    } else {
      const ObservationPrediction p = PredictObservation(pose, state_.Landmark(j));
      const ObservationPrediction J = config_.fej ? PredictObservation(pose, tracks_[j].first_estimate) : p;
      lin.push_back({j, Innovation(z[i], p.z), J.J_z_pose, J.J_z_landmark});
    }
    matched[j] = true;
    keys[i] = tracks_[j].key;
    ++tracks_[j].sightings;
    tracks_[j].seen_travel_m = travel_m_;
    tracks_[j].seen_heading_variance_rad2 = heading_variance_rad2_;
    ++tracks_[j].existence;
  }
  const EkfUpdateResult update =
      iterate_all ? IteratedUpdateState(state_, measured, R_, config_.update_iterations)
      : gated     ? IteratedUpdateState(state_, measured, R_, config_.relinearize_iterations, relinearize_gate_chi2_)
      : config_.invariant && !config_.fej ? InvariantUpdateState(state_, lin, R_)
                                          : UpdateState(state_, lin, R_);
  if (!update.applied && !(lin.empty() && measured.empty())) Record(event.t_s, "update_rejected", 1.0);
  if (gated && update.iterations > 1) Record(event.t_s, "update_relinearized", update.iterations);

  int created = 0, discarded = 0;
  for (size_t i = 0; i < obs.size(); ++i) created += target[i] == Association::kNew ? 1 : 0;
  births_ += created;
  if (first_birth_scan_ < 0 && created > 0) {
    first_birth_scan_ = scan_;
    first_scan_births_ = created;
  }
  const double prior_log_ratio = NewLandmarkPriorLogRatio();
  for (size_t i = 0; i < obs.size(); ++i) {
    if (target[i] == Association::kDiscard) ++discarded;
    if (target[i] != Association::kNew) continue;
    const int j = AddLandmark(state_, z[i], R_);
    const bool confirmed =
        known_ids_ || (config_.tentative_existence == ExistenceRule::kCounts && config_.confirm_sightings <= 1);
    LandmarkTrack track{next_key_++, known_ids_ ? obs[i].id : -1, 1, 0, 1, confirmed, event.t_s, state_.Landmark(j)};
    track.log_ratio = prior_log_ratio;
    track.pose_covariance_when_placed = state_.covariance.topLeftCorner<3, 3>();
    track.created_travel_m = track.seen_travel_m = travel_m_;
    track.seen_heading_variance_rad2 = heading_variance_rad2_;
    if (known_ids_) key_of_id_[obs[i].id] = track.key;
    keys[i] = track.key;
    tracks_.push_back(track);
  }
  // Landmarks seen in one scan are distinct for the rest of the run (never merged).
  if (!known_ids_)
    for (size_t a = 0; a < keys.size(); ++a)
      for (size_t b = a + 1; b < keys.size(); ++b)
        if (keys[a] >= 0 && keys[b] >= 0 && keys[a] != keys[b]) co_observed_.insert(std::minmax(keys[a], keys[b]));
  ManageExistence(matched, held, mu, event.t_s);
  // A merge whose gate may hold a fake is a loop closure on uncertain evidence: deferred
  // to the closure test (or, in the branch that tests without it, not made).
  bool uncertain_merge = false;
  const int merged =
      known_ids_ ? 0 : MergeDuplicates(blocks_closures_ || MayStartClosureTest(), &uncertain_merge);
  uncertain_merge_pending_ = uncertain_merge && MayStartClosureTest();
  if (!known_ids_ && config_.constellation_merges) scan_path_.emplace_back(travel_m_, state_.Pose());
  const int recognized = known_ids_ ? 0 : MergeConstellation(event.t_s);

  int confirmed = 0;
  for (const auto& t : tracks_) confirmed += t.confirmed ? 1 : 0;
  if (!estimate_.trajectory.empty() && estimate_.trajectory.back().t_s == event.t_s) {
    estimate_.trajectory.back().pose = state_.Pose();
    estimate_.trajectory.back().covariance = state_.covariance.topLeftCorner<3, 3>();
  }
  Record(event.t_s, "num_landmarks", confirmed);
  Record(event.t_s, "num_tentative", static_cast<double>(tracks_.size()) - confirmed);
  Record(event.t_s, "new_landmarks", created);
  Record(event.t_s, "discarded_observations", discarded);
  if (!known_ids_) Record(event.t_s, "merged_landmarks", merged);
  if (recognized > 0) Record(event.t_s, "constellation_merges", recognized);
  if (!known_ids_) Record(event.t_s, "held_pairings", static_cast<double>(std::count(held.begin(), held.end(), true)));
  if (update.applied) {
    Record(event.t_s, "nis", update.nis);
    Record(event.t_s, "nis_dof", update.dof);
  }
  // By key for now; Finish names them by the final landmark ids.
  for (size_t i = 0; i < obs.size(); ++i)
    estimate_.observation_assignments.push_back(
        {scan_, static_cast<int>(i), keys[i], target[i] == Association::kNew});
  ++scan_;
  return keys;
}

std::vector<bool> EkfSlam::HoldPairings(const std::vector<Eigen::Vector2d>& z, std::vector<int>& target) {
  if (known_ids_ || !config_.hold_uncertain_pairings || !(clutter_density_per_m2_ > 0))
    return std::vector<bool>(tracks_.size(), false);
  std::vector<int> keys(tracks_.size());
  TrackEvidence evidence(tracks_.size());
  for (size_t j = 0; j < tracks_.size(); ++j) {
    LandmarkTrack& t = tracks_[j];
    keys[j] = t.key;
    if (t.tracked && DriftedSincePlaced(static_cast<int>(j))) t.tracked = false;
    if (t.tracked) evidence[j] = t.track_log_fake;
  }
  const std::vector<bool> held =
      HoldUncertainPairings(state_, z, R_, keys, evidence,
                            {config_.gate_accept_chi2, clutter_density_per_m2_, config_.hold_evidence}, target, held_streak_);
  for (size_t j = 0; j < tracks_.size(); ++j)
    if (evidence[j]) tracks_[j].track_log_fake = *evidence[j];
  return held;
}

int EkfSlam::ResolveKey(int key) const {
  for (auto it = merged_into_.find(key); it != merged_into_.end(); it = merged_into_.find(key)) key = it->second;
  return key;
}

void EkfSlam::OnLandmarks(const LandmarkEvent& event) { ProcessLandmarks(event); }

Estimate EkfSlam::Finish() {
  revised_from_scan_ = -1;
  if (!closure_rival_.empty()) EndClosureTest(closure_log_ratio_ >= 0.0, estimate_.trajectory.back().t_s);
  std::map<int, int> id_of_key;  // known association: the landmark's true id names it
  for (const auto& [id, key] : key_of_id_) id_of_key[key] = id;
  for (ObservationAssignment& a : estimate_.observation_assignments) {
    if (a.landmark < 0) continue;
    a.landmark = ResolveKey(a.landmark);
    if (known_ids_) a.landmark = id_of_key.at(a.landmark);
  }
  for (size_t j = 0; j < tracks_.size(); ++j) {
    if (!tracks_[j].confirmed) continue;
    const int index = static_cast<int>(j);
    estimate_.landmarks.push_back({known_ids_ ? tracks_[j].id : tracks_[j].key, state_.Landmark(index),
                                   state_.LandmarkCovariance(index), true});
  }
  return std::move(estimate_);
}

ModuleInfo EkfSlamModule() {
  return MakeModuleInfo<EkfSlam, EkfSlamConfig>(
      "ekf-slam", "EKF-SLAM over point landmarks (known ids, nearest neighbour or JCBB; optional FEJ)",
      {.odometry = true, .landmarks = true}, &BindParams);
}

}  // namespace slambox
