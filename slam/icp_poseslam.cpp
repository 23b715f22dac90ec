#include "slam/icp_poseslam.hpp"

#include <Eigen/LU>

#include "core/error.hpp"
#include "core/odometry_model.hpp"

namespace slambox {

namespace {
constexpr double kDegToRad = M_PI / 180.0;

/// Fraction of the source points within radius_m of the target, the source placed at T.
double FitFraction(const IcpTarget& target, const std::vector<Eigen::Vector2d>& source, const SE2& T,
                   double radius_m) {
  int close = 0;
  for (const auto& p : source) {
    int index = -1;
    double d2 = 0.0;
    if (NearestByKdTree(target, T * p, &index, &d2) && d2 <= radius_m * radius_m) ++close;
  }
  return source.empty() ? 0.0 : static_cast<double>(close) / static_cast<double>(source.size());
}

const EnumNames<EdgeInformationSource> kEdgeInformationNames = {{EdgeInformationSource::kHessian, "hessian"},
                                                             {EdgeInformationSource::kFixed, "fixed"}};
}  // namespace

void BindParams(IcpPoseSlamConfig& c, ParamBinder& b) {
  BindIcpParams(c.icp, b);
  BindIcpParams(c.loop_icp, b, "loop_icp_");
  b.Bind("adaptive_gate", c.adaptive_gate, "-", "KISS-ICP adaptive correspondence gate for the front end");
  b.Bind("local_map_keyframes", c.local_map_keyframes, "-", "front end registers to this many keyframes before the latest too (0 = latest only)", AtLeast(0));
  b.Bind("local_map_voxel_m", c.local_map_voxel_m, "m", "voxel size of the front end's local map", Above(0));
  b.Bind("odometry_prior", c.odometry_prior, "-", "front-end ICP weighs the odometry guess (motion-model covariance) as a prior");
  b.Bind("guess_disagreement_m", c.guess_disagreement_m, "m", "odometry and constant-velocity guesses farther apart than this: ICP from both", Above(0));
  b.Bind("guess_disagreement_deg", c.guess_disagreement_deg, "deg", "... or turned farther apart than this", Above(0));
  b.Bind("guess_fit_radius_m", c.guess_fit_radius_m, "m", "between two ICP results, the one with more scan points this close to the target wins", Above(0));
  b.Bind("guess_switch_margin", c.guess_switch_margin, "-", "the constant-velocity result must fit this much better (fraction of points)", AtLeast(0));
  b.Bind("unconverged_icp_edges_from_odometry", c.unconverged_icp_edges_from_odometry, "-", "a keyframe whose ICP hit its iteration cap unconverged gets an odometry edge's information (motion model), ICP's pose");
  b.Bind("keyframe_distance_m", c.keyframe_distance_m, "m", "new keyframe after this much translation", Above(0));
  b.Bind("keyframe_angle_deg", c.keyframe_angle_deg, "deg", "new keyframe after this much rotation", Above(0));
  b.Bind("edge_information", c.edge_information, kEdgeInformationNames, "information of ICP edges");
  b.Bind("info_cap_sigma_xy_m", c.info_cap_sigma_xy_m, "m", "cap on Hessian information, translation", Above(0));
  b.Bind("info_cap_sigma_theta_deg", c.info_cap_sigma_theta_deg, "deg", "cap on Hessian information, heading",
         Above(0));
  b.Bind("fixed_sigma_xy_m", c.fixed_sigma_xy_m, "m", "fixed edge information, translation", Above(0));
  b.Bind("fixed_sigma_theta_deg", c.fixed_sigma_theta_deg, "deg", "fixed edge information, heading", Above(0));
  b.Bind("loop_min_travel_m", c.loop.min_travel_m, "m", "path between keyframes before a loop may close");
  b.Bind("loop_search_radius_m", c.loop.search_radius_m, "m", "base loop search radius");
  b.Bind("loop_radius_per_travel", c.loop.radius_per_travel, "m/m", "search radius growth per metre travelled");
  b.Bind("loop_window_sigmas", c.loop.window_sigmas, "-", "search window: this many std of the relative pose", Above(0));
  b.Bind("loop_max_search_radius_m", c.loop.max_search_radius_m, "m", "search radius cap");
  b.Bind("loop_search_angle_deg", c.loop.search_angle_deg, "deg", "base angular search window");
  b.Bind("loop_max_search_angle_deg", c.loop.max_search_angle_deg, "deg", "angular search window cap");
  b.Bind("loop_max_candidates", c.loop.max_candidates, "-", "loop verifications per keyframe");
  b.Bind("loop_min_keyframe_gap", c.loop.min_keyframe_gap, "-", "candidates at least this many keyframes apart");
  b.Bind("loop_submap_keyframes", c.loop_submap_keyframes, "-", "loop target: keyframes each side of the candidate");
  b.Bind("loop_min_source_points", c.loop_min_source_points, "-", "loop source: earlier keyframes (up to loop_submap_keyframes) join a scan with fewer points", AtLeast(0));
  b.Bind("loop_table_resolution_m", c.loop_table.resolution_m, "m", "correlative search grid cell", Above(0));
  b.Bind("loop_table_sigma_m", c.loop_table.sigma_m, "m", "correlative score: std of the point-to-map distance", Above(0));
  b.Bind("loop_table_levels", c.loop_table.levels, "-", "branch-and-bound levels", AtLeast(1));
  b.Bind("loop_table_unknown_score", c.loop_table.unknown_score, "-", "correlative score of a cell no ray of the submap crossed (0: scored as free space)", Between(0, 1));
  b.Bind("loop_min_score", c.loop_min_score, "-", "correlative score a closure needs");
  b.Bind("loop_runner_up_radius_m", c.loop_runner_up_radius_m, "m", "ambiguity: runner-up match farther than this from the best");
  b.Bind("loop_max_runner_up_ratio", c.loop_max_runner_up_ratio, "-", "ambiguity: runner-up score / best score must stay below this");
  b.Bind("loop_max_match_shift_m", c.loop_max_match_shift_m, "m", "ICP may move the correlative match at most this far");
  b.Bind("loop_reject_window_edge", c.loop_reject_window_edge, "-", "reject a correlative optimum on the search window's edge (the score still rises outwards)");
  b.Bind("loop_max_back_face_fraction", c.loop_max_back_face_fraction, "-", "reject a closure whose scan sees more than this fraction of its matched points from behind the target's surfaces (1 = off)", AtLeast(0));
  b.Bind("loop_back_face_max_distance_m", c.loop_back_face.max_distance_m, "m", "back-face check: a scan point this close to the target is matched", Above(0));
  b.Bind("loop_region", c.loop_region, "-", "region loop search where no candidate closed: old keyframes within the scan's median range, passes merged where they agree");
  b.Bind("loop_region_overlap_m", c.loop_region_passes.overlap_m, "m", "region: a pass's point with an admitted point this close is in their overlap", Above(0));
  b.Bind("loop_region_min_overlap", c.loop_region_passes.min_overlap_fraction, "-", "region: a pass must overlap the admitted ones with this fraction of its points (and score loop_min_score there)");
  b.Bind("loop_region_min_passes", c.loop_region_min_passes, "-", "region: searched only when this many passes are admitted", AtLeast(1));
  b.Bind("loop_region_max_search_radius_m", c.loop_region_max_search_radius_m, "m", "region: search radius cap (0 = loop_max_search_radius_m)", AtLeast(0));
  b.Bind("solve_every_keyframes", c.solve_every_keyframes, "-", "re-solve pending small closures after this many keyframes", AtLeast(1));
  b.Bind("solve_innovation_m", c.solve_innovation_m, "m", "a closure this far off the estimate is solved at once");
  b.Bind("loop_max_rms_m", c.loop.max_rms_m, "m", "loop ICP fitness: max RMS residual");
  b.Bind("loop_min_inlier_ratio", c.loop.min_inlier_ratio, "-", "loop ICP overlap: min inliers / points");
  b.Bind("loop_kernel", c.loop_kernel, RobustKernelNames(), "robust kernel on loop edges");
  b.Bind("loop_kernel_scale", c.loop_kernel_scale, "-", "Huber/Cauchy scale (whitened) or DCS Phi", Above(0));
  b.Bind("loop_accept_weight", c.loop_accept_weight, "-", "loop edges weighted below this count as rejected");
  b.Bind("solve_max_iterations", c.solve_max_iterations, "-", "Ceres iterations per solve");
  b.Bind("source_voxel_m", c.source_voxel_m, "m", "subsample scans (0 = off)");
  b.Bind("map_voxel_m", c.map_voxel_m, "m", "voxel size of the output map points");
  b.Bind("grid_resolution_m", c.grid_resolution_m, "m", "occupancy grid cell size (0 = no grid)");
  b.Bind("compute_covariance", c.compute_covariance, "-", "pose covariances (graph marginals + relative ICP/odometry)");
}

IcpPoseSlam::IcpPoseSlam(const IcpPoseSlamConfig& config)
    : config_(config), icp_(config.icp), loop_icp_(config.loop_icp) {
  local_map_icp_ = icp_;
  local_map_icp_.correspondence = IcpCorrespondence::kKdTree;
  solve_options_.loop_kernel = config.loop_kernel;
  solve_options_.kernel_scale = config.loop_kernel_scale;
  solve_options_.max_iterations = config.solve_max_iterations;
}

InformationCaps IcpPoseSlam::Caps() const {
  return {config_.info_cap_sigma_xy_m, config_.info_cap_sigma_theta_deg * kDegToRad};
}

void IcpPoseSlam::Start(const StreamHeader& header) {
  estimate_ = Estimate{};
  start_pose_ = header.start_pose;
  alpha_ = header.sensors.odometry ? header.sensors.odometry->alpha : std::array<double, 4>{};
  T_kf_robot_ = T_kf_last_scan_ = start_pose_;  // before the first keyframe: absolute
  T_last_scan_motion_ = SE2();
  guesses_switched_ = 0;
  odometry_cov_.setZero();
  relative_cov_.setZero();
  last_scan_cov_.setZero();
  path_m_ = 0.0;
  keyframes_.clear();
  graph_ = PoseGraph{};
  loop_record_of_edge_.clear();
  records_.clear();
  proposed_ = 0;
  loop_targets_.clear();
  keyframes_since_solve_ = 0;
  pending_closures_ = false;
  gate_ = AdaptiveThreshold{};
  gate_.config.initial_gate_m = icp_.max_correspondence_m;
  if (header.sensors.lidar) gate_.config.max_range_m = header.sensors.lidar->range_max_m;
  RecordPose(0.0);
}

void IcpPoseSlam::RecordPose(double t_s) {
  const int kf = static_cast<int>(keyframes_.size()) - 1;
  if (!records_.empty() && records_.back().t_s == t_s) records_.pop_back();
  records_.push_back({t_s, kf, T_kf_robot_, relative_cov_});
}

void IcpPoseSlam::OnOdometry(const OdometryEvent& odometry) {
  const OdometryIncrement u = Decompose(odometry.delta);
  const MotionPrediction p = PredictMotion(T_kf_robot_, u);
  const Eigen::Matrix3d M = p.J_pose_increment * IncrementCovariance(u, alpha_) * p.J_pose_increment.transpose();
  odometry_cov_ = p.J_pose_pose * odometry_cov_ * p.J_pose_pose.transpose() + M;
  relative_cov_ = p.J_pose_pose * relative_cov_ * p.J_pose_pose.transpose() + M;
  T_kf_robot_ = p.pose;
  path_m_ += odometry.delta.translation().norm();
  RecordPose(odometry.t_s);
}

void IcpPoseSlam::OnLaserScan(const LaserScanEvent& scan) {
  ScanPoints points = ScanToPoints(scan, {.voxel_size_m = config_.source_voxel_m});
  if (keyframes_.empty()) {
    AddKeyframe(scan, std::move(points), nullptr);
    return;
  }
  IcpConfig icp = config_.local_map_keyframes > 0 ? local_map_icp_ : icp_;
  if (config_.adaptive_gate) icp.max_correspondence_m = CorrespondenceGate(gate_);
  SE2 guess = T_kf_robot_;
  const bool has_noise_model = alpha_ != std::array<double, 4>{};
  std::optional<IcpPrior> prior;
  if (config_.odometry_prior && has_noise_model) {
    const OdometryIncrement u = Decompose(Between(T_kf_last_scan_, guess));
    const MotionPrediction p = PredictMotion(T_kf_last_scan_, u);
    const Eigen::Matrix3d cov = p.J_pose_pose * last_scan_cov_ * p.J_pose_pose.transpose() +
                                p.J_pose_increment * IncrementCovariance(u, alpha_) * p.J_pose_increment.transpose();
    // Floored so that it stays invertible (a robot at rest has a zero odometry covariance).
    prior = IcpPrior{guess, (cov + Eigen::Vector3d(1e-6, 1e-6, 1e-8).asDiagonal().toDenseMatrix()).inverse()};
  }
  IcpResult r = RegisterIcp(points.points, keyframe_target_, guess, icp, prior ? &*prior : nullptr);
  const SE2 cv_guess = T_kf_last_scan_ * T_last_scan_motion_;
  const SE2 gap = Between(cv_guess, guess);
  if (gap.translation().norm() > config_.guess_disagreement_m ||
      std::abs(gap.theta) > config_.guess_disagreement_deg * kDegToRad) {
    IcpResult r_cv = RegisterIcp(points.points, keyframe_target_, cv_guess, icp);
    const bool cv_ok = r_cv.converged || r_cv.num_inliers >= icp.min_inliers;
    const double f_cv = FitFraction(keyframe_target_, points.points, r_cv.T_target_source, config_.guess_fit_radius_m);
    const double f_odo = FitFraction(keyframe_target_, points.points, r.T_target_source, config_.guess_fit_radius_m);
    if (cv_ok && f_cv > f_odo + config_.guess_switch_margin) {
      r = std::move(r_cv);
      guess = cv_guess;
      ++guesses_switched_;
    }
  }
  const bool ok = r.converged || r.num_inliers >= icp.min_inliers;
  if (ok) {
    if (config_.adaptive_gate) UpdateThreshold(gate_, T_kf_last_scan_.inverse() * guess, T_kf_last_scan_.inverse() * r.T_target_source);
    T_kf_robot_ = r.T_target_source;
    if (config_.compute_covariance || config_.odometry_prior) relative_cov_ = IcpEdgeInformation(r, odometry_cov_, Caps()).inverse();
  }
  auto& d = estimate_.diagnostics;
  d["icp_iterations"].emplace_back(scan.t_s, r.iterations);
  d["icp_inliers"].emplace_back(scan.t_s, r.num_inliers);
  d["hessian_min_eigenvalue"].emplace_back(scan.t_s, r.eigenvalues(0));
  d["degenerate"].emplace_back(scan.t_s, r.degenerate ? 1.0 : 0.0);
  T_last_scan_motion_ = Between(T_kf_last_scan_, T_kf_robot_);
  T_kf_last_scan_ = T_kf_robot_;
  last_scan_cov_ = relative_cov_;
  const bool far = T_kf_robot_.translation().norm() >= config_.keyframe_distance_m ||
                   std::abs(T_kf_robot_.theta) >= config_.keyframe_angle_deg * kDegToRad;
  // A keyframe ICP cannot reach any more (sparse or changed surroundings) is replaced all
  // the same, joined by an odometry edge: otherwise every later scan would be registered to
  // an ever more distant keyframe and fail too.
  const bool measured = ok && (r.converged || !config_.unconverged_icp_edges_from_odometry);
  if (far) AddKeyframe(scan, std::move(points), measured ? &r : nullptr);
  else RecordPose(scan.t_s);
}

void IcpPoseSlam::AddKeyframe(const LaserScanEvent& scan, ScanPoints points, const IcpResult* edge_icp) {
  const int k = static_cast<int>(keyframes_.size());
  const SE2 pose = k == 0 ? T_kf_robot_ : graph_.poses.back() * T_kf_robot_;
  if (k > 0) {
    PoseGraphEdge e;
    e.from = k - 1;
    e.to = k;
    e.T_from_to = T_kf_robot_;
    if (!edge_icp) {  // ICP failed or did not converge: the wheel odometry's information, floored so it stays invertible
      e.information = (odometry_cov_ + Eigen::Vector3d(1e-6, 1e-6, 1e-8).asDiagonal().toDenseMatrix()).inverse();
      estimate_.diagnostics["odometry_edges"].emplace_back(scan.t_s, 1.0);
    } else {
      e.information = config_.edge_information == EdgeInformationSource::kFixed
                          ? FixedInformation(config_.fixed_sigma_xy_m, config_.fixed_sigma_theta_deg * kDegToRad)
                          : IcpEdgeInformation(*edge_icp, odometry_cov_, Caps());
    }
    graph_.edges.push_back(e);
    loop_record_of_edge_.push_back(-1);
  }
  graph_.poses.push_back(pose);
  if (config_.local_map_keyframes > 0) {
    std::vector<Eigen::Vector2d> local = points.points;
    for (int i = std::max(0, k - config_.local_map_keyframes); i < k; ++i) {
      const SE2 T_k_i = Between(pose, graph_.poses[static_cast<size_t>(i)]);
      for (const auto& p : keyframes_[static_cast<size_t>(i)].points.points) local.push_back(T_k_i * p);
    }
    std::vector<Eigen::Vector2d> thinned;
    for (int i : VoxelSubsample(local, config_.local_map_voxel_m)) thinned.push_back(local[static_cast<size_t>(i)]);
    keyframe_target_ = MakeCloudTarget(std::move(thinned));
  } else {
    IcpTargetConfig tc;
    tc.build_kd_tree = icp_.correspondence == IcpCorrespondence::kKdTree;
    keyframe_target_ = MakeScanTarget(points, scan, tc);
  }
  LaserScanEvent geometry = scan;
  geometry.ranges_m.assign(scan.ranges_m.size(), 0.0);  // only the beam layout is kept
  keyframes_.push_back({scan.t_s, std::move(points), std::move(geometry), path_m_});
  T_kf_robot_ = T_kf_last_scan_ = SE2();
  odometry_cov_.setZero();
  relative_cov_.setZero();
  last_scan_cov_.setZero();
  RecordPose(scan.t_s);
  if (k > 0) CloseLoops(scan.t_s);
}

void IcpPoseSlam::CloseLoops(double t_s) {
  const int k = static_cast<int>(keyframes_.size()) - 1;
  std::vector<double> path;
  for (const auto& kf : keyframes_) path.push_back(kf.path_m);
  // The window comes from the relative pose's uncertainty along the most certain path
  // through the graph (accepted closures included); beyond the caps it is the cap.
  std::vector<bool> use_edge(graph_.edges.size(), true);
  for (size_t i = 0; i < graph_.edges.size(); ++i) {
    const int rec = loop_record_of_edge_[i];
    if (rec >= 0) use_edge[i] = estimate_.loop_closures[static_cast<size_t>(rec)].accepted;
  }
  const double cap_sigma = config_.loop.max_search_radius_m / std::max(config_.loop.window_sigmas, 1e-9);
  const std::vector<Eigen::Matrix3d> rel = RelativeCovariances(graph_, k, use_edge, 2.0 * cap_sigma * cap_sigma);
  bool added = false;
  double innovation_m = 0.0;
  const std::vector<Eigen::Vector2d> source = LoopSource();
  for (const LoopCandidate& c : FindLoopCandidates(graph_.poses, path, k, config_.loop, rel)) {
    const LoopTarget& target = LoopTargetFor(c.keyframe);
    added = TryLoop(c.keyframe, source, target.table, [&]() -> const IcpTarget& { return target.cloud; }, c.radius_m,
                    c.angle_rad, &innovation_m);
    if (added) break;  // one closure per keyframe; the solve below moves the rest
  }
  if (!added && config_.loop_region) added = CloseLoopInRegion(source, rel, path, &innovation_m);
  estimate_.diagnostics["loop_closures_proposed"].emplace_back(t_s, proposed_);
  pending_closures_ = pending_closures_ || added;
  ++keyframes_since_solve_;
  // Closures that agree with the estimate change little: they are solved in batches.
  if ((added && innovation_m > config_.solve_innovation_m) ||
      (pending_closures_ && keyframes_since_solve_ >= config_.solve_every_keyframes)) {
    Solve();
    pending_closures_ = false;
    keyframes_since_solve_ = 0;
    loop_targets_.clear();  // the submaps moved
  }
}

PoseGraphSolveResult IcpPoseSlam::Solve(bool marginals) {
  PoseGraphSolveOptions options = solve_options_;
  options.compute_marginals = marginals;
  PoseGraphSolveResult s = SolvePoseGraph(graph_, options);
  int accepted = 0;
  for (size_t i = 0; i < graph_.edges.size(); ++i) {
    const int rec = loop_record_of_edge_[i];
    if (rec < 0) continue;
    const bool on = s.edge_weights.empty() || s.edge_weights[i] >= config_.loop_accept_weight;
    estimate_.loop_closures[static_cast<size_t>(rec)].accepted = on;
    accepted += on ? 1 : 0;
  }
  // Consistency of what the solution keeps: chi2 per edge over the front-end edges and
  // the accepted closures (pose_graph_chi2 counts the rejected closures' errors too).
  double chi2_kept = 0.0;
  int kept = 0;
  for (size_t i = 0; i < graph_.edges.size(); ++i) {
    const int rec = loop_record_of_edge_[i];
    if (rec >= 0 && !estimate_.loop_closures[static_cast<size_t>(rec)].accepted) continue;
    const PoseGraphEdge& e = graph_.edges[i];
    const Eigen::Vector3d err = EdgeError(graph_.poses[static_cast<size_t>(e.from)], graph_.poses[static_cast<size_t>(e.to)], e.T_from_to);
    chi2_kept += err.dot(e.information * err);
    ++kept;
  }
  const double t = keyframes_.back().t_s;
  estimate_.diagnostics["loop_closures_accepted"].emplace_back(t, accepted);
  estimate_.diagnostics["pose_graph_chi2"].emplace_back(t, s.chi2_final);
  estimate_.diagnostics["pose_graph_chi2_per_kept_edge"].emplace_back(t, kept ? chi2_kept / kept : 0.0);
  return s;
}

Estimate IcpPoseSlam::Finish() {
  estimate_.diagnostics["guesses_switched"].emplace_back(records_.empty() ? 0.0 : records_.back().t_s, guesses_switched_);
  std::vector<Eigen::Matrix3d> marginals;
  if (keyframes_.size() > 1) marginals = Solve(config_.compute_covariance).marginal_covariances;
  else if (keyframes_.size() == 1) marginals.assign(1, Eigen::Matrix3d::Zero());  // the anchor alone
  const bool with_cov = config_.compute_covariance && marginals.size() == keyframes_.size();
  for (const Record& r : records_) {
    PoseEstimate e{r.t_s, r.T_kf_robot, r.covariance, with_cov || r.keyframe < 0};
    if (r.keyframe >= 0) {
      const size_t k = static_cast<size_t>(r.keyframe);
      e.pose = graph_.poses[k] * r.T_kf_robot;
      if (with_cov) e.covariance = ComposeCovariance(graph_.poses[k], marginals[k], r.T_kf_robot, r.covariance);
    }
    e.has_covariance = e.has_covariance && config_.compute_covariance;
    if (!e.has_covariance) e.covariance.setZero();
    estimate_.trajectory.push_back(e);
  }
  std::vector<Eigen::Vector2d> all;
  std::vector<std::vector<Eigen::Vector2d>> scans;
  for (size_t k = 0; k < keyframes_.size(); ++k) {
    for (const auto& p : keyframes_[k].points.points) all.push_back(graph_.poses[k] * p);
    scans.push_back(keyframes_[k].points.points);
  }
  if (config_.map_voxel_m > 0)
    for (int i : VoxelSubsample(all, config_.map_voxel_m)) estimate_.map_points.push_back(all[static_cast<size_t>(i)]);
  else estimate_.map_points = std::move(all);
  if (config_.grid_resolution_m > 0 && !keyframes_.empty())
    estimate_.grid = BuildOccupancyGrid(graph_.poses, scans, {.resolution_m = config_.grid_resolution_m});
  PoseGraphView& view = estimate_.pose_graph;
  view.nodes = graph_.poses;
  for (const auto& kf : keyframes_) view.node_t_s.push_back(kf.t_s);
  for (size_t i = 0; i < graph_.edges.size(); ++i) {
    const int rec = loop_record_of_edge_[i];
    view.edges.push_back({graph_.edges[i].from, graph_.edges[i].to, graph_.edges[i].loop_closure,
                          rec < 0 || estimate_.loop_closures[static_cast<size_t>(rec)].accepted});
  }
  return std::move(estimate_);
}

ModuleInfo IcpPoseSlamModule() {
  return MakeModuleInfo<IcpPoseSlam, IcpPoseSlamConfig>(
      "icp-poseslam", "keyframe pose graph with ICP edges, ICP-verified loop closures, robust Ceres back-end",
      {.odometry = true, .lidar = true}, &BindParams);
}

}  // namespace slambox
