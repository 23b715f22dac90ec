// `EkfSlam`'s place recognition from constellations (constellation_merges, unknown ids).
// After drift the filter maps a revisited place a second time: the landmarks it created
// within the last 2, 4 or 8 range_max of travel are matched as one rigid shape onto the
// landmarks last seen before that (slam/constellation_match.hpp). The match is the place's
// motion T from where the filter put it to where the old map has it: the robot and the
// landmarks it saw within the window move by T, the landmarks mapped during the drift by
// their share of it (constellation_spread, RevisitShares), they take on the fit's uncertainty
// of T, and each matched pair, now close, is merged by exact conditioning (the older landmark
// kept); through the correlations the rest of the map follows, as after a known-id
// re-observation.
#include <algorithm>
#include <cmath>
#include <optional>

#include "slam/constellation_revisit.hpp"
#include "slam/ekf_slam.hpp"
#include "slam/range_bearing.hpp"

namespace slambox {

namespace {
/// The fit's uncertainty as a covariance of the robot's corrected pose T x_r: Procrustes over
/// k pairs, each differing by two detections' noise (2 sigma^2 per axis), puts 2 sigma^2 / k on
/// the centroid's translation and 2 sigma^2 / sum |r - r_c|^2 on the rotation, carried to the
/// robot by its lever arm v = perp(T x_r - T r_c).
Eigen::Matrix3d FitCovarianceAtRobot(const ConstellationMatch& match, const std::vector<Eigen::Vector2d>& recent_xy,
                                     double sigma2_m2, const SE2& robot) {
  const SE2& T = match.T_old_recent;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const auto& [o, r] : match.pairs) centroid += recent_xy[r];
  const double k = static_cast<double>(match.pairs.size());
  centroid /= k;
  double spread_m2 = 0.0;
  for (const auto& [o, r] : match.pairs) spread_m2 += (recent_xy[r] - centroid).squaredNorm();
  const Eigen::Vector2d arm = T * robot.translation() - T * centroid;
  const Eigen::Vector3d v(-arm.y(), arm.x(), 1.0);
  Eigen::Matrix3d Q = v * v.transpose() * (2.0 * sigma2_m2 / spread_m2);
  Q.topLeftCorner<2, 2>() += Eigen::Matrix2d::Identity() * (2.0 * sigma2_m2 / k);
  return Q;
}

/// The robot moves by T and each landmark l by the part of T its share s_l gives
/// (PartOfMotion; 1 for the window's, RevisitShares for old ones mapped during the drift, 0
/// for the rest): their means, and their covariance with them (P <- A P A^T, A rotating each
/// moved position's rows by its own angle s_l theta); then they take on Q as one rigid motion
/// about the robot, in proportion to their share (+ J Q J^T, J the motion's Jacobian: identity
/// for the robot, s_l [I, perp(m - x_r)] for a landmark m). Merging the pairs without the move,
/// linearized on a heading several degrees off, sent `forest` seed 14 10 m the wrong way;
/// scaling the covariance by the match's NIS instead left the scripted revisit 0.3 m off
/// (tests/slam/ekf_slam_constellation_test.cpp).
void MoveByShares(EkfSlamState& state, const std::vector<double>& shares, const SE2& T, const Eigen::Matrix3d& Q) {
  struct Moved {
    Eigen::Index row;  // the position's first row
    double share;
    SE2 motion;        // PartOfMotion(T, share)
  };
  std::vector<Moved> moved = {{0, 1.0, T}};  // the robot's position, then each moved landmark's
  for (size_t l = 0; l < shares.size(); ++l)
    if (shares[l] > 0.0) moved.push_back({3 + 2 * static_cast<Eigen::Index>(l), shares[l], PartOfMotion(T, shares[l])});
  Eigen::MatrixXd& P = state.covariance;
  for (const Moved& m : moved) P.middleRows<2>(m.row) = m.motion.rotation() * P.middleRows<2>(m.row);
  for (const Moved& m : moved) P.middleCols<2>(m.row) = P.middleCols<2>(m.row) * m.motion.rotation().transpose();
  const SE2 robot = T * state.Pose();
  state.mean.head<3>() = robot.vector();
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(state.mean.size(), 3);
  J.topLeftCorner<3, 3>().setIdentity();
  for (const Moved& m : moved) {
    if (m.row == 0) continue;
    const Eigen::Vector2d xy = m.motion * Eigen::Vector2d(state.mean.segment<2>(m.row));
    state.mean.segment<2>(m.row) = xy;
    J.block<2, 2>(m.row, 0) = m.share * Eigen::Matrix2d::Identity();
    J(m.row, 2) = -m.share * (xy - robot.translation()).y();
    J(m.row + 1, 2) = m.share * (xy - robot.translation()).x();
  }
  P.noalias() += J * Q * J.transpose();
}
}  // namespace

int EkfSlam::MergeConstellation(double t_s) {
  if (!config_.constellation_merges || known_ids_) return 0;
  while (!scan_path_.empty() && travel_m_ - scan_path_.front().first > RevisitWidestWindow(range_max_m_)) scan_path_.pop_front();
  if (!(config_.merge_probability > 0.0)) return 0;
  // While a closure is tested the branches must differ only in that closure; the rival
  // makes no closure at all.
  if (blocks_closures_ || !closure_rival_.empty()) return 0;
  std::vector<RevisitLandmark> confirmed;
  std::vector<int> index, keys;  // per confirmed landmark: its index in tracks_, its key
  for (size_t j = 0; j < tracks_.size(); ++j) {
    const LandmarkTrack& t = tracks_[j];
    if (!t.confirmed) continue;
    confirmed.push_back({state_.Landmark(static_cast<int>(j)), t.created_travel_m, t.seen_travel_m, t.seen_heading_variance_rad2});
    index.push_back(static_cast<int>(j));
    keys.push_back(t.key);
  }
  const RevisitSettings settings{travel_m_, heading_variance_rad2_, state_.Pose().translation(), range_max_m_,
                                 RevisitTolerance(R_, range_max_m_, config_.gate_accept_chi2), gate_probability_,
                                 config_.constellation_max_hypotheses};
  if (!RevisitWorthSearching(confirmed, keys, settings, constellation_searched_)) return 0;
  std::optional<Revisit> revisit = FindRevisit(confirmed, settings);
  if (!revisit) return 0;
  std::vector<bool> moved(tracks_.size(), true);  // the robot and the window's landmarks: all but the old
  for (const int c : revisit->old) moved[index[c]] = false;
  std::vector<Eigen::Vector2d> window_xy;  // every landmark of the window, tentative ones too
  for (size_t j = 0; j < tracks_.size(); ++j)
    if (moved[j]) window_xy.push_back(state_.Landmark(static_cast<int>(j)));
  std::vector<SE2> scan_poses;  // newest first
  for (auto it = scan_path_.rbegin(); it != scan_path_.rend() && travel_m_ - it->first <= revisit->window_m; ++it)
    scan_poses.push_back(it->second);
  const std::vector<double> old_shares =
      config_.constellation_spread ? RevisitShares(*revisit, confirmed, settings) : std::vector<double>();
  const double log_missed = LogMissedUnderRevisit(
      *revisit, confirmed, window_xy, scan_poses, settings.tolerance_m, old_shares,
      [&](const Eigen::Vector2d& z) { return ExpectedInView(z) ? DetectionProbability(detection_, z.x()) : 0.0; });
  if (log_missed < std::log(1.0 - gate_probability_)) return 0;
  const ConstellationMatch& match = revisit->match;
  Record(t_s, "constellation_chance", match.chance);
  std::vector<Eigen::Vector2d> recent_xy;
  for (const int c : revisit->recent) recent_xy.push_back(confirmed[c].xy);
  const double sigma2 = std::max(R_(0, 0), range_max_m_ * range_max_m_ * R_(1, 1));
  std::vector<double> shares(moved.begin(), moved.end());
  for (size_t o = 0; o < old_shares.size(); ++o) shares[index[revisit->old[o]]] = old_shares[o];
  MoveByShares(state_, shares, match.T_old_recent, FitCovarianceAtRobot(match, recent_xy, sigma2, state_.Pose()));
  std::vector<std::pair<int, int>> pair_keys;  // (old, recent): indices shift as landmarks are removed
  for (const auto& [o, r] : match.pairs) pair_keys.emplace_back(keys[revisit->old[o]], keys[revisit->recent[r]]);
  auto index_of = [&](int key) {
    for (size_t j = 0; j < tracks_.size(); ++j)
      if (tracks_[j].key == key) return static_cast<int>(j);
    return -1;
  };
  int merged = 0;
  for (const auto& [old_key, recent_key] : pair_keys) {
    if (SeenTogether(old_key, recent_key)) continue;
    const int a = index_of(old_key), b = index_of(recent_key);
    if (a >= 0 && b >= 0 && MergeTrackInto(a, b)) ++merged;
  }
  return merged;
}

}  // namespace slambox
