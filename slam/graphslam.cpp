#include "slam/graphslam.hpp"

#include <algorithm>
#include <iterator>

#include "core/chi_square.hpp"
#include "core/error.hpp"
#include "core/odometry_model.hpp"
#include "slam/growth_replay.hpp"
#include "slam/keyframe_decimation.hpp"
#include "slam/leftover_association.hpp"
#include "slam/range_bearing.hpp"

namespace slambox {

void BindParams(GraphSlamConfig& c, ParamBinder& b) {
  b.Bind("keyframe_every_odometry", c.keyframe_every_odometry, "steps",
         "a landmark scan makes a keyframe after this many odometry steps (0 = off)", AtLeast(0));
  b.Bind("keyframe_distance_m", c.keyframe_distance_m, "m",
         "... or after this much travel (0 = off; both off = every scan)", AtLeast(0));
  b.Bind("solve_every_keyframes", c.solve_every_keyframes, "keyframes",
         "also solve during the run every this many keyframes (0 = off); with any solve during the run, new keyframes "
         "are composed onto the solved graph with the front end's motion, and the solved graph is one more guess of "
         "the end solve (the lowest chi2 is kept)",
         AtLeast(0));
  b.Bind("periodic_max_keyframes", c.periodic_max_keyframes, "keyframes",
         "a solve during the run or of a replay keeps every k-th keyframe (and the last), k the smallest that "
         "leaves at most this many, the odometry between them composed, and comes every solve_every_keyframes x k "
         "keyframes (0 = all keyframes, every solve_every_keyframes)",
         AtLeast(0));
  b.Bind("replay_chi2_per_residual", c.replay_chi2_per_residual, "-",
         "where the end solve's best guess fits with a chi2 per residual above this (its expectation is below 1), the "
         "graph's growth is replayed with solves every replay_every_keyframes / 2, x 1 and x 2 keyframes, three more "
         "guesses (0 = never)",
         AtLeast(0));
  b.Bind("replay_when_guesses_disagree", c.replay_when_guesses_disagree, "-",
         "also replay the graph's growth where two guesses of the end solve stopped in different minima (a fold can "
         "fit its noise model)");
  b.Bind("frontend_jump_prob", c.frontend_jump_prob, "-",
         "a graph solved as it grows (periodic solves, replays) composes new keyframes with the front end's motion, "
         "except where it is farther from the odometry than the chi2_3 quantile of this probability (a jump of the "
         "filter): the odometry's motion there (0 = never)");
  b.Bind("replay_every_keyframes", c.replay_every_keyframes, "keyframes",
         "the middle interval of the replays (past periodic_max_keyframes each solve is of a decimated graph and the "
         "interval grows with its stride)",
         AtLeast(2));
  b.Bind("relocalized_guess", c.relocalized_guess, "-",
         "the end solve also starts from the front end's poses re-localized against its final map (landmarks held) "
         "and keeps the guess of the lowest chi2");
  b.Bind("max_iterations", c.max_iterations, "-", "Ceres iterations per solve", AtLeast(1));
  b.Bind("compute_covariance", c.compute_covariance, "-", "marginal covariances (selected inversion of the information matrix)");
  b.Bind("huber_scale", c.huber_scale, "sigma", "Huber loss on range-bearing residuals (0 = none)", AtLeast(0));
  b.Bind("smoother_merges", c.smoother_merges, "-",
         "unknown ids: at the end, merge duplicate landmarks jointly under the smoother's marginals (gate and threshold "
         "from merge_probability, density the map's own)");
  b.Bind("smoother_leftovers", c.smoother_leftovers, "-",
         "unknown ids, after the smoother merges: a detection the front end left out (held, or of a deleted tentative "
         "landmark) joins the one landmark of the smoothed map in its gate (gate_accept_chi2), if that gate expects fewer "
         "clutter or unmapped landmarks than its miss probability");
  b.Bind("smoother_merges_max_landmarks", c.smoother_merges_max_landmarks, "-",
         "above this many landmarks after the split, the joint search (cost ~ candidates^2 x pairs) is skipped and "
         "the front end's association kept", AtLeast(0));
  BindParams(c.frontend, b);  // the EKF front end's association settings, same names
}

GraphSlam::GraphSlam(const GraphSlamConfig& config) : config_(config), frontend_(config.frontend) {
  if (!(config.frontend_jump_prob >= 0 && config.frontend_jump_prob < 1))
    throw InputError("--set algo.graphslam.frontend_jump_prob", 0, "must lie in [0, 1)", "e.g. 0.99, or 0 to always compose the front end's motion");
}

void GraphSlam::Start(const StreamHeader& header) {
  frontend_.Start(header);
  jump_gate_chi2_ = config_.frontend_jump_prob > 0 ? ChiSquareQuantile(config_.frontend_jump_prob, 3.0) : 0.0;
  alpha_ = header.sensors.odometry ? header.sensors.odometry->alpha : std::array<double, 4>{};
  const LandmarkSensorConfig sensor = header.sensors.landmarks.value_or(LandmarkSensorConfig{});
  known_ids_ = config_.frontend.association == EkfAssociation::kKnown ||
               (config_.frontend.association == EkfAssociation::kAuto && sensor.known_ids);
  graph_ = LandmarkGraph{};
  graph_.observation_covariance = config_.frontend.observation_noise_scale * ObservationCovariance(sensor);
  graph_.poses.push_back(header.start_pose);
  frontend_poses_ = {header.start_pose};
  keyframe_t_s_ = {0.0};
  samples_.clear();
  solved_landmarks_.clear();
  merged_into_.clear();
  rejected_merges_.clear();
  footprint_ = {sensor.range_max_m, 0.5 * sensor.fov_deg * M_PI / 180.0};
  split_ = {};
  dropped_.clear();
  scan_keyframe_.clear();
  scan_t_s_.clear();
  scan_first_observation_.clear();
  scan_z_.clear();
  T_keyframe_robot_ = SE2();
  covariance_since_keyframe_.setZero();
  steps_since_keyframe_ = 0;
  travel_since_keyframe_m_ = 0.0;
  skipped_scans_ = 0;
  last_periodic_solve_ = 0;
  estimate_ = Estimate{};
}

void GraphSlam::OnOdometry(const OdometryEvent& odometry) {
  frontend_.OnOdometry(odometry);
  // Propagate the relative pose and its covariance from the keyframe (Thrun Table 5.6).
  const OdometryIncrement u = Decompose(odometry.delta);
  const MotionPrediction p = PredictMotion(T_keyframe_robot_, u);
  const Eigen::Matrix3d M = config_.frontend.motion_noise_scale * IncrementCovariance(u, alpha_);
  covariance_since_keyframe_ = p.J_pose_pose * covariance_since_keyframe_ * p.J_pose_pose.transpose() +
                               p.J_pose_increment * M * p.J_pose_increment.transpose();
  T_keyframe_robot_ = p.pose;
  ++steps_since_keyframe_;
  travel_since_keyframe_m_ += std::abs(u.trans);
  samples_.push_back({odometry.t_s, static_cast<int>(graph_.poses.size()) - 1, T_keyframe_robot_,
                      covariance_since_keyframe_});
}

bool GraphSlam::WantKeyframe() const {
  if (steps_since_keyframe_ == 0) return false;  // observations attach to the current keyframe
  const bool by_steps = config_.keyframe_every_odometry > 0;
  const bool by_distance = config_.keyframe_distance_m > 0;
  if (!by_steps && !by_distance) return true;
  return (by_steps && steps_since_keyframe_ >= config_.keyframe_every_odometry) ||
         (by_distance && travel_since_keyframe_m_ >= config_.keyframe_distance_m);
}

void GraphSlam::AddKeyframe(double t_s) {
  const int from = static_cast<int>(graph_.poses.size()) - 1;
  graph_.odometry.push_back({from, T_keyframe_robot_, covariance_since_keyframe_});
  // Initial guess: the front end's filtered pose; when solving periodically, the last
  // keyframe's (possibly solved) pose composed with the front end's motion since (the
  // odometry's where the front end jumped: ComposedMotion, slam/growth_replay.hpp).
  frontend_poses_.push_back(frontend_.state().Pose());
  graph_.poses.push_back(config_.solve_every_keyframes > 0
                             ? ComposedMotion(graph_.poses[from], frontend_poses_[from], frontend_poses_.back(),
                                              graph_.odometry.back(), jump_gate_chi2_)
                             : frontend_poses_.back());
  keyframe_t_s_.push_back(t_s);
  if (!samples_.empty() && samples_.back().t_s == t_s)  // this odometry event is the keyframe itself
    samples_.back() = {t_s, from + 1, SE2(), Eigen::Matrix3d::Zero()};
  T_keyframe_robot_ = SE2();
  covariance_since_keyframe_.setZero();
  steps_since_keyframe_ = 0;
  travel_since_keyframe_m_ = 0.0;
}

void GraphSlam::OnLandmarks(const LandmarkEvent& event) {
  const std::vector<int> keys = frontend_.ProcessLandmarks(event);
  if (WantKeyframe()) AddKeyframe(event.t_s);
  const int keyframe = static_cast<int>(graph_.poses.size()) - 1;
  scan_keyframe_.push_back(keyframe);
  scan_t_s_.push_back(event.t_s);
  scan_first_observation_.push_back(graph_.observations.size());
  scan_z_.emplace_back();
  const bool used = steps_since_keyframe_ == 0;  // between keyframes a scan is not used
  if (used) {
    for (const LandmarkObservation& o : event.observations) scan_z_.back().emplace_back(o.range_m, o.bearing_rad);
    for (size_t i = 0; i < keys.size(); ++i)
      if (keys[i] >= 0) graph_.observations.push_back({keyframe, keys[i], scan_z_.back()[i]});
  } else {
    ++skipped_scans_;
  }
  if (frontend_.revised_from_scan() >= 0) RebuildFromScan(frontend_.revised_from_scan(), frontend_.partial_estimate());
  // Every K kept keyframes: past the cap, the decimated graph grows by one keyframe per
  // `stride`, so the interval grows with it and each solve costs about the same.
  if (used && config_.solve_every_keyframes > 0 &&
      GrowingGraphSolveDue(keyframe, last_periodic_solve_, config_.solve_every_keyframes, config_.periodic_max_keyframes)) {
    const LandmarkGraphSolution s =
        Solve({.keyframe_stride = DecimationStride(keyframe, config_.periodic_max_keyframes)});
    estimate_.diagnostics["solver_iterations"].emplace_back(event.t_s, s.iterations);
    last_periodic_solve_ = keyframe;
  }
}

void GraphSlam::RebuildFromScan(int from, const Estimate& front) {
  // Both branches of the test numbered their new landmarks from one counter, so the losing
  // branch's keys may name other landmarks in the winner: every observation of the scans
  // since the fork is taken again from the winner's assignments (in scan order).
  graph_.observations.resize(scan_first_observation_.at(static_cast<size_t>(from)));
  const std::vector<ObservationAssignment>& a = front.observation_assignments;
  auto it = std::lower_bound(a.begin(), a.end(), from, [](const ObservationAssignment& x, int s) { return x.scan < s; });
  for (size_t scan = static_cast<size_t>(from); scan < scan_keyframe_.size(); ++scan) {
    scan_first_observation_[scan] = graph_.observations.size();
    for (; it != a.end() && it->scan == static_cast<int>(scan); ++it)
      if (it->landmark >= 0 && !scan_z_[scan].empty())
        graph_.observations.push_back({scan_keyframe_[scan], it->landmark, scan_z_[scan].at(static_cast<size_t>(it->index))});
  }
  // Keyframes made since the fork: the front end's guess is the winner's filtered poses
  // (with periodic solves the graph's own guess is the solved graph's and stays).
  const double t_fork = scan_t_s_[static_cast<size_t>(from)];
  const std::vector<PoseEstimate>& trajectory = front.trajectory;
  for (size_t k = 1; k < graph_.poses.size(); ++k) {
    if (keyframe_t_s_[k] < t_fork) continue;
    auto p = std::upper_bound(trajectory.begin(), trajectory.end(), keyframe_t_s_[k],
                              [](double t, const PoseEstimate& q) { return t < q.t_s; });
    if (p == trajectory.begin()) continue;
    frontend_poses_[k] = std::prev(p)->pose;
    if (config_.solve_every_keyframes == 0) graph_.poses[k] = frontend_poses_[k];
  }
  solved_landmarks_.clear();  // keyed by names that may now mean other landmarks
}

int GraphSlam::GraphKey(int frontend_key) const {
  int key = frontend_.ResolveKey(frontend_key);
  for (auto it = merged_into_.find(key); it != merged_into_.end(); it = merged_into_.find(key)) key = it->second;
  return key;
}

LandmarkGraphSolution GraphSlam::Solve(const SolveRequest& request) {
  // Landmarks: the front end's confirmed ones (tentative and deleted ones are left out,
  // and so are their observations); the guess is the last solution or the EKF's mean.
  graph_.landmarks.clear();
  // Observations of a landmark the front end merged into another now constrain that one.
  for (RangeBearingConstraint& o : graph_.observations) o.landmark = GraphKey(o.landmark);
  const auto& tracks = frontend_.tracks();
  for (size_t j = 0; j < tracks.size(); ++j) {
    if (!tracks[j].confirmed || merged_into_.count(tracks[j].key)) continue;
    const auto solved = solved_landmarks_.find(tracks[j].key);
    graph_.landmarks[tracks[j].key] =
        solved != solved_landmarks_.end() ? solved->second : frontend_.state().Landmark(static_cast<int>(j));
  }
  for (const auto& [key, guess] : split_.guesses) {
    if (merged_into_.count(key)) continue;
    const auto solved = solved_landmarks_.find(key);
    graph_.landmarks[key] = solved != solved_landmarks_.end() ? solved->second : guess;
  }
  const LandmarkGraphOptions options{.max_iterations = config_.max_iterations,
                                     .compute_covariance = config_.compute_covariance && request.covariance,
                                     .huber_scale = config_.huber_scale,
                                     .joint_landmark_covariance = request.joint_landmarks,
                                     .hold_landmarks = request.hold_landmarks};
  LandmarkGraphSolution s;
  if (request.keyframe_stride > 1) {
    DecimatedGraph d = DecimateKeyframes(graph_, request.keyframe_stride);
    s = SolveLandmarkGraph(d.graph, options);
    SpreadDecimatedSolution(d, graph_);
  } else {
    s = SolveLandmarkGraph(graph_, options);
  }
  solved_landmarks_ = graph_.landmarks;
  return s;
}

std::map<std::pair<int, int>, int> GraphSlam::JoinLeftovers(const LandmarkGraphSolution& s, const Estimate& front) {
  std::vector<LeftoverDetection> detections;
  std::vector<std::pair<int, int>> where;  // (scan, detection index) of each
  for (const ObservationAssignment& a : front.observation_assignments) {
    const auto scan = static_cast<size_t>(a.scan);
    if (scan >= scan_z_.size() || scan_z_[scan].empty()) continue;  // not a keyframe scan
    const int keyframe = scan_keyframe_[scan];
    const int key = a.landmark >= 0 ? GraphKey(SegmentKey(split_, a.landmark, keyframe)) : -1;
    if (key >= 0 && graph_.landmarks.count(key)) continue;
    detections.push_back({keyframe, scan_z_[scan].at(static_cast<size_t>(a.index))});
    where.emplace_back(a.scan, a.index);
  }
  const std::vector<int> keys = AssociateLeftovers(
      graph_, s, detections,
      {config_.frontend.gate_accept_chi2, 1.0 - frontend_.gate_probability(), frontend_.FakeDensity()});
  std::map<std::pair<int, int>, int> joined;
  for (size_t i = 0; i < keys.size(); ++i) {
    if (keys[i] < 0) continue;
    graph_.observations.push_back({detections[i].keyframe, keys[i], detections[i].z});
    joined[where[i]] = keys[i];
  }
  // Keyframe order, as everything else in the graph keeps its observations.
  std::stable_sort(graph_.observations.begin(), graph_.observations.end(),
                   [](const RangeBearingConstraint& u, const RangeBearingConstraint& v) { return u.keyframe < v.keyframe; });
  return joined;
}

Estimate GraphSlam::Finish() {
  const Estimate front = frontend_.Finish();  // ends a running closure test by the scans so far
  if (frontend_.revised_from_scan() >= 0) RebuildFromScan(frontend_.revised_from_scan(), front);
  if (config_.solve_every_keyframes > 0 || config_.relocalized_guess || config_.replay_chi2_per_residual > 0)
    StartFromTheBestGuess();
  LandmarkGraphSolution s;
  int merges = 0;
  std::map<std::pair<int, int>, int> joined_leftovers;  // (scan, detection index) -> landmark key
  bool skipped = false;
  if (MergesInSmoother()) {
    // The front end's association, then every re-observation after leaving view split
    // off (slam/reobservation_split.hpp) and merged back jointly by the smoother.
    Solve({});
    // Not a key the front end ever issued: a merged-away key still resolves to the landmark
    // it was merged into (GraphKey), so a segment named by it would join that landmark.
    int first_free_key = frontend_.next_key();
    for (const auto& o : graph_.observations) first_free_key = std::max(first_free_key, o.landmark + 1);
    const std::vector<RangeBearingConstraint> unsplit = graph_.observations;
    split_ = SplitAtReobservations(graph_, footprint_, AmbiguityTest(), first_free_key);
    if (graph_.landmarks.size() + split_.guesses.size() > static_cast<size_t>(config_.smoother_merges_max_landmarks)) {
      // Too large for the joint search: the front end's association stands.
      graph_.observations = unsplit;
      split_ = {};
      skipped = true;
      s = Solve({.covariance = true});
    } else {
      s = Solve({.joint_landmarks = true});
      merges = MergeInSmoother(s);
      s = Solve({.covariance = true});  // the marginals of the final graph (the rounds computed the joint landmark block only)
      if (config_.smoother_leftovers && !(joined_leftovers = JoinLeftovers(s, front)).empty()) s = Solve({.covariance = true});
    }
    // A split-off segment seen at one keyframe and merged with nothing constrains nothing
    // (its two residuals meet its two unknowns) and is no evidence of a landmark: after
    // leaving view, one detection is what a fake pairing of the front end looks like.
    std::map<int, int> count;
    for (const auto& o : graph_.observations) ++count[o.landmark];
    for (const auto& [key, guess] : split_.guesses)
      if (graph_.landmarks.count(key) && count[key] < 2) graph_.landmarks.erase(key), dropped_.insert(key);
  } else {
    s = Solve({.covariance = true});
  }
  const double t_end = samples_.empty() ? 0.0 : samples_.back().t_s;
  auto& d = estimate_.diagnostics;
  d["solver_iterations"].emplace_back(t_end, s.iterations);
  d["chi2_final"].emplace_back(t_end, s.chi2_final);
  d["observations_left_out"].emplace_back(t_end, s.observations_left_out);
  d["chi2_per_residual"].emplace_back(t_end, s.num_residuals > 0 ? s.chi2_final / s.num_residuals : 0.0);
  d["solution_usable"].emplace_back(t_end, s.usable ? 1.0 : 0.0);
  d["num_keyframes"].emplace_back(t_end, static_cast<double>(graph_.poses.size()));
  d["skipped_scans"].emplace_back(t_end, skipped_scans_);
  d["smoother_merges"].emplace_back(t_end, merges);
  if (MergesInSmoother()) {
    d["smoother_merges_refused"].emplace_back(t_end, static_cast<double>(rejected_merges_.size()));
    d["smoother_merges_skipped"].emplace_back(t_end, skipped ? 1.0 : 0.0);
    d["smoother_leftovers_joined"].emplace_back(t_end, static_cast<double>(joined_leftovers.size()));
  }
  // The front end associates (and the smoother merges): named by the same landmark ids as below.
  estimate_.observation_assignments = front.observation_assignments;
  for (ObservationAssignment& a : estimate_.observation_assignments) {
    if (a.landmark >= 0) {
      a.landmark = GraphKey(SegmentKey(split_, a.landmark, scan_keyframe_.at(a.scan)));
      if (dropped_.count(a.landmark)) a.landmark = -1;
    }
    if (const auto j = joined_leftovers.find({a.scan, a.index}); j != joined_leftovers.end()) a.landmark = j->second;
  }
  for (const char* name : {"num_landmarks", "nis", "nis_dof"})
    if (front.diagnostics.count(name)) d[std::string("frontend_") + name] = front.diagnostics.at(name);

  // Trajectory: keyframe 0, then every odometry event through its keyframe. For
  // T = T_k * T_kr with independent parts: core/se2's ComposeCovariance.
  const bool cov = s.covariance_ok;
  estimate_.trajectory.push_back({0.0, graph_.poses[0], Eigen::Matrix3d::Zero(), cov});
  for (const OdometrySample& sample : samples_) {
    const SE2& T_k = graph_.poses[sample.keyframe];
    const SE2& T_kr = sample.T_keyframe_robot;
    const Eigen::Matrix3d P =
        cov ? ComposeCovariance(T_k, s.pose_covariances[sample.keyframe], T_kr, sample.covariance)
            : Eigen::Matrix3d::Zero();
    estimate_.trajectory.push_back({sample.t_s, T_k * T_kr, 0.5 * (P + P.transpose()), cov});
  }
  std::map<int, int> id_of_key;  // known ids: the true id names a landmark
  for (const auto& track : frontend_.tracks()) id_of_key[track.key] = track.id;
  for (const auto& [key, m] : graph_.landmarks) {
    const auto c = s.landmark_covariances.find(key);
    estimate_.landmarks.push_back({known_ids_ ? id_of_key.at(key) : key, m,
                                   c != s.landmark_covariances.end() ? c->second : Eigen::Matrix2d::Zero(),
                                   c != s.landmark_covariances.end()});
  }
  for (size_t i = 0; i < graph_.poses.size(); ++i) {
    estimate_.pose_graph.node_t_s.push_back(keyframe_t_s_[i]);
    estimate_.pose_graph.nodes.push_back(graph_.poses[i]);
    if (i > 0) estimate_.pose_graph.edges.push_back({static_cast<int>(i) - 1, static_cast<int>(i), false, true});
  }
  return std::move(estimate_);
}

ModuleInfo GraphSlamModule() {
  return MakeModuleInfo<GraphSlam, GraphSlamConfig>(
      "graphslam", "landmark GraphSLAM: full smoothing of keyframes and landmarks with Ceres (EKF front end)",
      {.odometry = true, .landmarks = true}, &BindParams);
}

}  // namespace slambox
