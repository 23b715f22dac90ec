// `FastSlam`'s place recognition from constellations (constellation_merges, unknown ids).
// A particle associates an old landmark only if its own pose lies inside that landmark's
// gate; after drift, with the cloud collapsed onto one ancestor, none does, and lap 2 maps
// the place a second time (slam/README_fastslam.md). The revisit is found as ekf-slam finds
// it (slam/constellation_revisit.hpp), in the best particle's map: its recent landmarks match
// old ones as one rigid shape. Then each particle that holds at least three of the matched
// pairs fits its own motion T to them (AlignPointToPoint), moves its pose and the landmarks
// it saw within the window by T, those it saw since the matched old ones by their share of T
// (constellation_spread, RevisitShare; covariances rotated), and merges each pair by
// conditioning the two landmark Gaussians on being one point (ConditionOnEqual; given the
// path a particle's landmarks are independent, so there is no cross term). A particle that
// holds fewer pairs (another lineage mapped the place differently) is left alone: its weight
// decides.
#include <algorithm>
#include <cmath>
#include <optional>

#include "core/chi_square.hpp"
#include "slam/constellation_revisit.hpp"
#include "slam/fastslam.hpp"
#include "slam/fastslam_closure.hpp"
#include "slam/icp_closed_form.hpp"
#include "slam/landmark_merge.hpp"
#include "slam/range_bearing.hpp"

namespace slambox {

namespace {

/// Moves the particle's pose by T, and every landmark seen within `window_m` of travel (but the
/// old ones of `pairs`) by T; with `spread`, every landmark seen after the paired old ones as
/// the particle's path relaxes under T (RelaxParticle, dead reckoning's variances `drift`,
/// within the drift's gate `gate_chi2`);
/// then merges each (old, recent) pair into the old key. Returns the merges,
/// 0 if the particle holds fewer than 3 pairs.
int MoveAndMerge(FastSlamParticle& p, const std::vector<std::pair<int, int>>& pairs, double travel_m, double window_m,
                 bool spread, std::span<const DriftSample> drift, double gate_chi2) {
  std::vector<Eigen::Vector2d> recent_xy, old_xy;
  std::vector<std::pair<int, int>> held;
  double paired_rad2 = 0.0;  // the paired old landmarks' largest heading variance at their sighting
  for (const auto& [old_key, recent_key] : pairs) {
    const LandmarkGaussian* a = FindLandmark(p.map, old_key);
    const LandmarkGaussian* b = FindLandmark(p.map, recent_key);
    if (a == nullptr || b == nullptr) continue;
    old_xy.push_back(a->mean);
    recent_xy.push_back(b->mean);
    held.emplace_back(old_key, recent_key);
    paired_rad2 = std::max(paired_rad2, a->seen_heading_variance_rad2);
  }
  if (held.size() < 3) return 0;
  const std::vector<double> weights(held.size(), 1.0);
  const SE2 T = AlignPointToPoint(recent_xy, old_xy, weights);
  const auto is_held = [&](int key) {
    return std::any_of(held.begin(), held.end(), [&](const auto& pair) { return pair.first == key; });
  };
  // With `spread` the particle's path since the paired old landmarks relaxes (slam/fastslam_closure.hpp);
  // without (or without drift to spread it by) the window moves with the robot.
  const std::vector<DriftStep> steps = spread ? PathSince(p.path.get(), paired_rad2, drift) : std::vector<DriftStep>();
  if (!spread || !RelaxParticle(p, T * p.pose, steps, p.pose_covariance + PathDriftCovariance(steps, p.pose.translation()),
                                gate_chi2, paired_rad2, is_held)) {
    MoveParticle(p, T, [&](int key, const LandmarkGaussian& lm) {
      return !is_held(key) && travel_m - lm.seen_travel_m <= window_m;
    });
  }
  int merged = 0;
  for (const auto& [old_key, recent_key] : held) {
    LandmarkGaussian keep = *FindLandmark(p.map, old_key);
    const LandmarkGaussian& gone = *FindLandmark(p.map, recent_key);
    Eigen::Vector4d x;
    x << keep.mean, gone.mean;
    Eigen::Matrix4d P = Eigen::Matrix4d::Zero();
    P.topLeftCorner<2, 2>() = keep.covariance;
    P.bottomRightCorner<2, 2>() = gone.covariance;
    Eigen::VectorXd xd = x;
    Eigen::MatrixXd Pd = P;
    if (!ConditionOnEqual(xd, Pd, 0, 2)) continue;
    keep.mean = xd.head<2>();
    keep.covariance = Pd.topLeftCorner<2, 2>();
    keep.counter += gone.counter;  // both counted sightings of one landmark
    keep.log_ratio = std::max(keep.log_ratio, gone.log_ratio);
    keep.seen_travel_m = std::max(keep.seen_travel_m, gone.seen_travel_m);
    keep.seen_heading_variance_rad2 = std::max(keep.seen_heading_variance_rad2, gone.seen_heading_variance_rad2);
    SetLandmark(p.map, old_key, keep);
    EraseLandmark(p.map, recent_key);
    p.merges = std::make_shared<const KeyMerge>(KeyMerge{recent_key, old_key, p.merges});
    ++merged;
  }
  return merged;
}

}  // namespace

int FastSlam::MergeConstellation(double t_s) {
  if (!config_.constellation_merges || update_.known_ids) return 0;
  scan_travel_.emplace_back(travel_m_, t_s);
  while (!scan_travel_.empty() && travel_m_ - scan_travel_.front().first > RevisitWidestWindow(update_.range_max_m))
    scan_travel_.pop_front();
  const int best = BestParticle();
  const FastSlamParticle& b = particles_[best];
  std::vector<RevisitLandmark> confirmed;
  std::vector<int> keys;
  ForEachLandmark(b.map, [&](int key, const LandmarkGaussian& lm) {
    if (!update_.Confirmed(lm)) return;
    confirmed.push_back({lm.mean, lm.created_travel_m, lm.seen_travel_m, lm.seen_heading_variance_rad2});
    keys.push_back(key);
  });
  const RevisitSettings settings{travel_m_,
                                 heading_variance_rad2_,
                                 b.pose.translation(),
                                 update_.range_max_m,
                                 RevisitTolerance(update_.R, update_.range_max_m,
                                                  ChiSquareQuantile(config_.constellation_gate_prob, 2.0)),
                                 config_.constellation_gate_prob,
                                 config_.constellation_max_hypotheses};
  if (!RevisitWorthSearching(confirmed, keys, settings, constellation_searched_)) return 0;
  const std::optional<Revisit> revisit = FindRevisit(confirmed, settings);
  if (!revisit) return 0;
  // Refused if old landmarks the match puts in view of the window's scans were missed there.
  std::vector<bool> is_old(keys.size(), false);
  for (const int c : revisit->old) is_old[c] = true;
  std::vector<Eigen::Vector2d> window_xy;  // every landmark but the old, tentative ones too
  ForEachLandmark(b.map, [&](int key, const LandmarkGaussian& lm) {
    const auto at = std::lower_bound(keys.begin(), keys.end(), key);
    if (at != keys.end() && *at == key && is_old[at - keys.begin()]) return;
    window_xy.push_back(lm.mean);
  });
  std::vector<SE2> scan_poses;  // the best particle's pose at each scan of the window, newest first
  const PathNode* node = b.path.get();
  for (auto it = scan_travel_.rbegin(); it != scan_travel_.rend() && travel_m_ - it->first <= revisit->window_m; ++it) {
    while (node != nullptr && node->t_s > it->second) node = node->parent.get();
    if (node == nullptr) break;
    scan_poses.push_back(node->pose);
  }
  const std::vector<double> old_shares =
      config_.constellation_spread ? RevisitShares(*revisit, confirmed, settings) : std::vector<double>();
  const double log_missed =
      LogMissedUnderRevisit(*revisit, confirmed, window_xy, scan_poses, settings.tolerance_m, old_shares,
                            [&](const Eigen::Vector2d& z) {
        const bool in_view = z.x() <= update_.range_max_m - update_.visibility_margin_m && std::abs(z.y()) <= update_.half_fov_rad;
        return in_view ? DetectionProbability(update_.detection, z.x()) : 0.0;
      });
  if (log_missed < std::log(1.0 - config_.constellation_gate_prob)) return 0;
  Diagnose(t_s, "constellation_chance", revisit->match.chance);
  std::vector<std::pair<int, int>> pairs;  // (old key, recent key)
  for (const auto& [o, r] : revisit->match.pairs) pairs.emplace_back(keys[revisit->old[o]], keys[revisit->recent[r]]);
  int merged_best = 0;
  for (size_t i = 0; i < particles_.size(); ++i) {
    const int merged = MoveAndMerge(particles_[i], pairs, travel_m_, revisit->window_m, config_.constellation_spread, drift_,
                                    update_.drift_gate_chi2);
    if (static_cast<int>(i) == best) merged_best = merged;
  }
  // Every path gets the pose at t_s (moved or not), so that all paths keep the same times.
  for (FastSlamParticle& p : particles_) p.path = ExtendPath(p.path, t_s, p.pose);
  return merged_best;
}

}  // namespace slambox
