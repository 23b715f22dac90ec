#include "slam/fastslam.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <tuple>

#include "core/chi_square.hpp"
#include "core/error.hpp"
#include "core/limits.hpp"
#include "core/odometry_model.hpp"
#include "slam/constellation_revisit.hpp"
#include "slam/fastslam_closure.hpp"
#include "slam/landmark_existence.hpp"
#include "slam/particle_weights.hpp"
#include "slam/range_bearing.hpp"

namespace slambox {

namespace {

void Validate(const FastSlamConfig& c, const std::string& name) {
  const std::string where = "--set algo." + name;
  auto fail = [&](const std::string& field, const std::string& problem, const std::string& fix) {
    throw InputError(where + "." + field, 0, problem, fix);
  };
  if (c.particles < 1 || c.particles > limits::kMaxParticles)
    fail("particles", "needs 1 .. " + std::to_string(limits::kMaxParticles) + " particles, got " + std::to_string(c.particles),
         "set particles to e.g. 100");
  if (!(c.new_landmark_gate_chi2 > 0)) fail("new_landmark_gate_chi2", "must be positive", "e.g. 25");
  if (!(c.neff_threshold >= 0 && c.neff_threshold <= 1)) fail("neff_threshold", "must lie in [0, 1]", "e.g. 0.5");
  if (c.detection_rate_bands < 1 || c.detection_rate_bands > 1000)
    fail("detection_rate_bands", "needs 1 .. 1000 bands", "e.g. 10");
  if (!(c.existence_error_prob > 0 && c.existence_error_prob < 0.5))
    fail("existence_error_prob", "must lie in (0, 0.5)", "e.g. 0.01");
  if (!(c.constellation_gate_prob > 0.5 && c.constellation_gate_prob < 1))
    fail("constellation_gate_prob", "must lie in (0.5, 1)", "e.g. 0.99");
  if (c.constellation_max_hypotheses < 1) fail("constellation_max_hypotheses", "must be positive", "e.g. 100000");
  if (c.motion_noise_scale < 0) fail("motion_noise_scale", "must not be negative", "e.g. 1");
  if (c.snapshot_period_s < 0) fail("snapshot_period_s", "must not be negative", "0 disables snapshots");
  if (c.visibility_margin_m < 0 || c.candidate_margin_m < 0) fail("visibility_margin_m", "margins must not be negative", "e.g. 0.5");
}

// Seed of this module's generator from the stream seed and the module name (FNV-1a), so
// fastslam1 and fastslam2 draw different but reproducible noise.
std::mt19937_64 MakeGenerator(std::uint64_t seed, const std::string& name) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char ch : name) h = (h ^ ch) * 1099511628211ull;
  std::seed_seq seq{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                    static_cast<std::uint32_t>(h), static_cast<std::uint32_t>(h >> 32)};
  return std::mt19937_64(seq);
}

}  // namespace

FastSlam::FastSlam(const FastSlamConfig& config, bool fastslam2)
    : config_(config), fastslam2_(fastslam2), name_(fastslam2 ? "fastslam2" : "fastslam1") {
  Validate(config_, name_);
}

void FastSlam::Start(const StreamHeader& header) {
  if (!header.sensors.landmarks)
    throw InputError(header.scenario_name, 0, name_ + " needs landmark observations but the stream has none",
                     "add a sensors.landmarks block to the scenario");
  const LandmarkSensorConfig& lm = *header.sensors.landmarks;
  alpha_ = header.sensors.odometry ? header.sensors.odometry->alpha : std::array<double, 4>{};
  update_.R = ObservationCovariance(lm);
  update_.fastslam2 = fastslam2_;
  update_.known_ids = config_.use_known_ids && lm.known_ids;
  update_.log_p0 = -std::log(2.0 * M_PI) - 0.5 * std::log(update_.R.determinant()) - 0.5 * config_.new_landmark_gate_chi2;
  update_.range_max_m = lm.range_max_m;
  update_.half_fov_rad = 0.5 * lm.fov_deg * M_PI / 180.0;
  clutter_per_scan_ = lm.clutter_per_scan;
  const bool pd_stated = lm.detection_prob_known;
  update_.estimate_detection_rate =
      config_.estimate_detection_rate == DetectionRateUse::kAlways ||
      (config_.estimate_detection_rate == DetectionRateUse::kAuto && !pd_stated);
  update_.detection = MakeDetectionRate(lm.range_max_m, config_.detection_rate_bands, lm.detection_prob);
  update_.confirmed_counter = config_.report_min_counter;
  update_.keep_confirmed_unseen_m =
      config_.keep_confirmed ? RevisitWidestWindow(lm.range_max_m) : std::numeric_limits<double>::infinity();
  update_.existence = config_.existence == FastSlamExistence::kSequentialTest ||
                              (config_.existence == FastSlamExistence::kAuto && !pd_stated)
                          ? ExistenceRule::kSequentialTest
                          : ExistenceRule::kCounts;
  update_.wald = MakeWaldThresholds(config_.existence_error_prob, config_.existence_error_prob);
  update_.clutter_density_per_m2 =
      lm.clutter_per_scan / (update_.range_max_m * update_.range_max_m * update_.half_fov_rad);
  births_ = 0.0;
  update_.visibility_margin_m = config_.visibility_margin_m;
  // The closure trusts the old landmarks' association: with unknown ids a pairing that fails
  // the innovation test inside the p0 gate is as likely another landmark (Victoria Park:
  // agreement 0.9956 -> 0.908); there the revisit is found by its constellation.
  update_.closure_old_after_m = config_.closure_spread && update_.known_ids ? RevisitWidestWindow(lm.range_max_m)
                                                                           : std::numeric_limits<double>::infinity();
  update_.closure_gate_prob = config_.constellation_gate_prob;
  update_.drift_gate_chi2 = ChiSquareQuantile(config_.constellation_gate_prob, 3.0);
  update_.candidate_margin_m = config_.candidate_margin_m;
  rng_ = MakeGenerator(header.seed + static_cast<std::uint64_t>(static_cast<std::int64_t>(config_.seed_offset)), name_);
  estimate_ = Estimate{};
  cloud_.clear();
  particles_.assign(config_.particles, FastSlamParticle{});
  const PathPtr start = std::make_shared<PathNode>(0.0, header.start_pose, nullptr);
  for (size_t i = 0; i < particles_.size(); ++i) {
    particles_[i].pose = header.start_pose;
    particles_[i].origin = static_cast<int>(i);
    particles_[i].log_weight = -std::log(static_cast<double>(particles_.size()));
    particles_[i].path = start;
  }
  travel_m_ = heading_variance_rad2_ = 0.0;
  drift_.clear();
  scan_travel_.clear();
  constellation_searched_.clear();
  RecordCloud(0.0);
  next_snapshot_s_ = 0.0;
  scan_ = 0;
}

void FastSlam::OnOdometry(const OdometryEvent& odometry) {
  const OdometryIncrement u = Decompose(odometry.delta);
  // Decompose folds backward motion, so a noisy in-place turn has rot1 near 0, not ±pi.
  const Eigen::Matrix3d M = config_.motion_noise_scale * IncrementCovariance(u, alpha_);
  const Eigen::Vector3d sd = M.diagonal().cwiseSqrt();
  travel_m_ += std::abs(u.trans);
  heading_variance_rad2_ += M(0, 0) + M(2, 2);  // rot1 and rot2 turn the heading
  drift_.push_back({odometry.t_s, heading_variance_rad2_, (drift_.empty() ? 0.0 : drift_.back().translation_m2) + M(1, 1)});
  std::normal_distribution<double> n01(0.0, 1.0);
  for (FastSlamParticle& p : particles_) {
    if (fastslam2_) {  // keep the Gaussian prior of the proposal: P' = G P G^T + V M V^T
      const MotionPrediction m = PredictMotion(p.pose, u);
      p.pose = m.pose;
      p.pose_covariance = m.J_pose_pose * p.pose_covariance * m.J_pose_pose.transpose() +
                          m.J_pose_increment * M * m.J_pose_increment.transpose();
    } else {  // sample the motion model (Thrun Table 5.6): noisy (rot1, trans, rot2)
      const OdometryIncrement noisy{u.rot1 + sd(0) * n01(rng_), u.trans + sd(1) * n01(rng_),
                                    u.rot2 + sd(2) * n01(rng_)};
      p.pose = PredictMotion(p.pose, noisy).pose;
    }
    p.path = ExtendPath(p.path, odometry.t_s, p.pose);
  }
  RecordCloud(odometry.t_s);
}

double FakeDetectionDensity(double clutter_per_scan, double births, int scans_done, double footprint_m2) {
  return clutter_per_scan / footprint_m2 + UnmappedLandmarkDensity(births, scans_done, clutter_per_scan, footprint_m2, 1.0);
}

void FastSlam::OnLandmarks(const LandmarkEvent& landmarks) {
  const double t = landmarks.t_s;
  if (config_.new_landmark_p0 == NewLandmarkP0::kDensity && !update_.known_ids)
    update_.fake_density_per_m2 = FakeDetectionDensity(
        clutter_per_scan_, births_, scan_, update_.range_max_m * update_.range_max_m * update_.half_fov_rad);
  update_.new_log_ratio = NewLandmarkPriorLogRatio(births_, scan_ + 1.0, clutter_per_scan_);
  update_.travel_m = travel_m_;
  update_.drift = drift_;
  update_.heading_variance_rad2 = heading_variance_rad2_;
  double created = 0.0;
  int closures = 0;  // particles corrected for a loop closure
  const int best = BestParticle();
  std::vector<std::pair<double, bool>> expected;  // the best particle's, for the detection rate
  for (size_t i = 0; i < particles_.size(); ++i) {
    FastSlamParticle& p = particles_[i];
    ParticleUpdateSummary s = UpdateParticle(p, landmarks.observations, update_, rng_);
    created += s.created;
    closures += s.closure ? 1 : 0;
    if (static_cast<int>(i) == best) expected = std::move(s.expected);
    p.assignments = std::make_shared<AssignmentNode>(scan_, std::move(s.landmark_of), std::move(s.creates), p.assignments);
    p.log_weight += s.log_weight_factor;
    p.log_likelihood += s.log_weight_factor;
    if (fastslam2_) p.path = ExtendPath(p.path, t, p.pose);  // the pose was resampled at t
  }
  births_ += created / static_cast<double>(particles_.size());
  if (closures > 0) Diagnose(t, "closure_particles", closures);
  for (const auto& [range_m, seen] : expected) CountExpected(update_.detection, range_m, seen);
  ++scan_;
  std::vector<double> log_w(particles_.size());
  for (size_t i = 0; i < particles_.size(); ++i) log_w[i] = particles_[i].log_weight;
  const std::vector<double> w = NormalizeLogWeights(log_w);
  for (size_t i = 0; i < particles_.size(); ++i) particles_[i].log_weight = std::log(w[i]);
  const int recognized = MergeConstellation(t);
  if (recognized > 0) Diagnose(t, "constellation_merges", recognized);
  if (fastslam2_ || recognized > 0) RecordCloud(t);

  const bool snapshot = config_.snapshot_period_s > 0 && t >= next_snapshot_s_;
  if (snapshot) Diagnose(t, "map_tree_nodes", static_cast<double>(MapTreeNodes()));  // peak: before resampling
  const double neff = EffectiveSampleSize(w);
  const bool resample = neff < config_.neff_threshold * static_cast<double>(particles_.size());
  if (resample) {  // children share their parent's map tree and path: O(M) pointer copies
    const std::vector<int> chosen = LowVarianceResample(w, rng_);
    std::vector<FastSlamParticle> next;
    next.reserve(particles_.size());
    for (int i : chosen) next.push_back(particles_[i]);
    for (FastSlamParticle& p : next) p.log_weight = -std::log(static_cast<double>(next.size()));
    particles_ = std::move(next);
  }
  std::set<int> origins;
  for (const FastSlamParticle& p : particles_) origins.insert(p.origin);
  Diagnose(t, "neff", neff);
  Diagnose(t, "distinct_ancestors", static_cast<double>(origins.size()));
  Diagnose(t, "resampled", resample ? 1.0 : 0.0);
  Diagnose(t, "landmarks", particles_[BestParticle()].map.size);

  if (snapshot) {
    ParticleSnapshot snap{t, {}, {}};
    const std::vector<double> w_now = NormalizeLogWeights([&] {
      std::vector<double> lw;
      for (const FastSlamParticle& p : particles_) lw.push_back(p.log_weight);
      return lw;
    }());
    for (const FastSlamParticle& p : particles_) snap.poses.push_back(p.pose);
    snap.weights = w_now;
    estimate_.particles.push_back(std::move(snap));
    next_snapshot_s_ = t + config_.snapshot_period_s;
  }
}

namespace {

// Weighted mean of the particles' poses (circular for the heading) and their weighted
// scatter about it; `pose(i)` is particle i's pose.
template <class PoseOf>
PoseEstimate WeightedPoseMean(double t_s, const std::vector<double>& w, PoseOf pose) {
  double x = 0, y = 0, s = 0, c = 0;
  for (size_t i = 0; i < w.size(); ++i) {
    const SE2& q = pose(i);
    x += w[i] * q.x, y += w[i] * q.y, s += w[i] * std::sin(q.theta), c += w[i] * std::cos(q.theta);
  }
  PoseEstimate e{t_s, SE2(x, y, std::atan2(s, c)), Eigen::Matrix3d::Zero(), true};
  for (size_t i = 0; i < w.size(); ++i) {
    const SE2& q = pose(i);
    const Eigen::Vector3d d(q.x - x, q.y - y, NormalizeAngle(q.theta - e.pose.theta));
    e.covariance += w[i] * d * d.transpose();
  }
  return e;
}

}  // namespace

// The cloud's mean and covariance; FastSLAM 2.0 adds the mean of the particles' own prior
// covariances (law of total covariance).
void FastSlam::RecordCloud(double t_s) {
  std::vector<double> log_w;
  for (const FastSlamParticle& p : particles_) log_w.push_back(p.log_weight);
  const std::vector<double> w = NormalizeLogWeights(log_w);
  PoseEstimate e = WeightedPoseMean(t_s, w, [&](size_t i) -> const SE2& { return particles_[i].pose; });
  for (size_t i = 0; i < w.size(); ++i) e.covariance += w[i] * particles_[i].pose_covariance;
  if (!cloud_.empty() && cloud_.back().t_s == t_s) cloud_.back() = e;
  else cloud_.push_back(e);
}

int FastSlam::BestParticle() const {
  int best = 0;
  for (size_t i = 1; i < particles_.size(); ++i) {
    const FastSlamParticle &p = particles_[i], &b = particles_[best];
    if (std::tie(p.log_weight, p.log_likelihood) > std::tie(b.log_weight, b.log_likelihood)) best = static_cast<int>(i);
  }
  return best;
}

size_t FastSlam::MapTreeNodes() const {
  std::vector<const LandmarkTree*> trees;
  for (const FastSlamParticle& p : particles_) trees.push_back(&p.map);
  return CountDistinctNodes(trees);
}

// The smoothed path: at each time, the weighted mean and covariance of the final
// particles' ancestral poses (every particle's path has the same times).
std::vector<PoseEstimate> FastSlam::PathMean() const {
  std::vector<double> log_w;
  for (const FastSlamParticle& p : particles_) log_w.push_back(p.log_weight);
  const std::vector<double> w = NormalizeLogWeights(log_w);
  std::vector<std::vector<const PathNode*>> paths;
  for (const FastSlamParticle& p : particles_) paths.push_back(PathPoses(p.path));
  std::vector<PoseEstimate> out;
  for (size_t k = 0; k < paths.front().size(); ++k)
    out.push_back(WeightedPoseMean(paths.front()[k]->t_s, w, [&](size_t i) -> const SE2& { return paths[i][k]->pose; }));
  return out;
}

double FastSlam::CoalescedUntil() const {
  // Walk every final particle's path back in step (newest first) to the first node they
  // all share: their most recent common ancestor. -1 if there is none.
  std::vector<const PathNode*> at;
  for (const FastSlamParticle& p : particles_) at.push_back(p.path.get());
  while (!at.empty()) {
    double newest = -std::numeric_limits<double>::infinity();
    for (const PathNode* n : at) {
      if (n == nullptr) return -1.0;
      newest = std::max(newest, n->t_s);
    }
    if (std::all_of(at.begin(), at.end(), [&](const PathNode* n) { return n == at.front(); })) return newest;
    for (const PathNode*& n : at)
      if (n->t_s == newest) n = n->parent.get();
  }
  return -1.0;
}

Estimate FastSlam::Finish() {
  if (particles_.empty()) return std::move(estimate_);
  const FastSlamParticle& best = particles_[BestParticle()];
  if (config_.trajectory == FastSlamTrajectory::kMean) {
    estimate_.trajectory = cloud_;
  } else if (config_.trajectory == FastSlamTrajectory::kPathMean) {
    estimate_.trajectory = PathMean();
  } else {  // the best particle's ancestry, with the cloud's covariance at the same times
    // Where every final particle descends from one pose node the set holds one path: the
    // filtered cloud's covariance at that time says nothing about the error of this
    // (smoothed) path, so those poses get no covariance (no confident NEES from a
    // depleted set; Bailey et al. 2006).
    const double coalesced_until_s = CoalescedUntil();
    estimate_.diagnostics["coalesced_until_s"].emplace_back(best.path ? best.path->t_s : 0.0, coalesced_until_s);
    size_t k = 0;
    // The path moved as its map did at each closure and revisit (slam/fastslam_closure.hpp).
    for (PoseEstimate e : RelaxedPath(best.path, best.relaxations.get(), drift_)) {
      while (k < cloud_.size() && cloud_[k].t_s < e.t_s) ++k;
      if (k < cloud_.size() && cloud_[k].t_s == e.t_s && e.t_s > coalesced_until_s)
        e.covariance = cloud_[k].covariance, e.has_covariance = true;
      estimate_.trajectory.push_back(e);
    }
  }
  // The best particle's associations (per-particle association: its lineage's), oldest first.
  std::vector<const AssignmentNode*> scans;
  for (const AssignmentNode* n = best.assignments.get(); n; n = n->parent.get()) scans.push_back(n);
  std::map<int, int> merged_into;  // removed key -> key it was merged into (constellation_merges)
  for (const KeyMerge* m = best.merges.get(); m; m = m->parent.get()) merged_into[m->removed] = m->kept;
  auto resolve = [&](int key) {
    for (auto it = merged_into.find(key); it != merged_into.end(); it = merged_into.find(key)) key = it->second;
    return key;
  };
  for (auto it = scans.rbegin(); it != scans.rend(); ++it)
    for (size_t i = 0; i < (*it)->landmark.size(); ++i)
      estimate_.observation_assignments.push_back(
          {(*it)->scan, static_cast<int>(i), resolve((*it)->landmark[i]), (*it)->created[i] != 0});
  ForEachLandmark(best.map, [&](int key, const LandmarkGaussian& lm) {
    if (!update_.known_ids && !update_.Confirmed(lm)) return;
    estimate_.landmarks.push_back({key, lm.mean, lm.covariance, true});
  });
  return std::move(estimate_);
}

ModuleInfo FastSlam1Module() {
  return MakeModuleInfo<FastSlam1, FastSlamConfig>(
      "fastslam1", "FastSLAM 1.0: particles with landmark EKFs, motion-model proposal, shared map trees",
      {.odometry = true, .landmarks = true}, &BindParams);
}

ModuleInfo FastSlam2Module() {
  return MakeModuleInfo<FastSlam2, FastSlam2Config>(
      "fastslam2", "FastSLAM 2.0: particles with landmark EKFs, proposal including the observations",
      {.odometry = true, .landmarks = true}, &BindParams);
}

}  // namespace slambox
