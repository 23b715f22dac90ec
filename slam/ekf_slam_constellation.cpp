// `EkfSlam`'s place recognition from constellations (constellation_merges, unknown ids).
// After drift the filter maps a revisited place a second time: the landmarks it created
// within the last 2, 4 or 8 range_max of travel are matched as one rigid shape onto the
// landmarks last seen before that (slam/constellation_match.hpp). The match is the place's
// motion T from where the filter put it to where the old map has it: the robot and the
// landmarks it saw within the window move by T, take on the fit's uncertainty of T, and
// each matched pair, now close, is merged by exact conditioning (the older landmark kept);
// through the correlations the rest of the map follows, as after a known-id re-observation.
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "core/chi_square.hpp"
#include "slam/constellation_match.hpp"
#include "slam/ekf_slam.hpp"
#include "slam/range_bearing.hpp"

namespace slambox {

namespace {
/// [range_max] the windows of travel tried, narrowest first.
constexpr std::array<double, 3> kWindows = {2.0, 4.0, 8.0};

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

/// The robot and the landmarks `moved` flags move by T: their means, and their covariance with
/// them (P <- A P A^T, A rotating their position rows by T's angle); then they take on Q as one
/// rigid motion about the robot (+ J Q J^T, J the motion's Jacobian: identity for the robot,
/// [I, perp(m - x_r)] for a landmark m). Merging the pairs without the move, linearized on a
/// heading several degrees off, sent `forest` seed 14 10 m the wrong way; scaling the covariance
/// by the match's NIS instead left the scripted revisit 0.3 m off
/// (tests/slam/ekf_slam_constellation_test.cpp).
void MoveRigidly(EkfSlamState& state, const std::vector<bool>& moved, const SE2& T, const Eigen::Matrix3d& Q) {
  const Eigen::Matrix2d Rt = T.rotation();
  std::vector<Eigen::Index> rows = {0};  // the robot's position, then each moved landmark's
  for (size_t l = 0; l < moved.size(); ++l)
    if (moved[l]) rows.push_back(3 + 2 * static_cast<Eigen::Index>(l));
  Eigen::MatrixXd& P = state.covariance;
  for (const Eigen::Index row : rows) P.middleRows<2>(row) = Rt * P.middleRows<2>(row);
  for (const Eigen::Index row : rows) P.middleCols<2>(row) = P.middleCols<2>(row) * Rt.transpose();
  const SE2 robot = T * state.Pose();
  state.mean.head<3>() = robot.vector();
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(state.mean.size(), 3);
  J.topLeftCorner<3, 3>().setIdentity();
  for (const Eigen::Index row : rows) {
    if (row == 0) continue;
    const Eigen::Vector2d m = T * Eigen::Vector2d(state.mean.segment<2>(row));
    state.mean.segment<2>(row) = m;
    J.block<2, 2>(row, 0).setIdentity();
    J(row, 2) = -(m - robot.translation()).y();
    J(row + 1, 2) = (m - robot.translation()).x();
  }
  P.noalias() += J * Q * J.transpose();
}
}  // namespace

int EkfSlam::MergeConstellation(double t_s) {
  if (!config_.constellation_merges || known_ids_) return 0;
  while (!scan_path_.empty() && travel_m_ - scan_path_.front().first > kWindows.back() * range_max_m_) scan_path_.pop_front();
  if (!(config_.merge_probability > 0.0)) return 0;
  // While a closure is tested the branches must differ only in that closure; the rival
  // makes no closure at all.
  if (blocks_closures_ || !closure_rival_.empty()) return 0;
  // The windows widen (2, 4, 8 range_max) until one decides: a footprint swept once holds
  // few landmarks (`forest`: about 5), too few to rise above the chance of the motions tried.
  const double sigma2 = std::max(R_(0, 0), range_max_m_ * range_max_m_ * R_(1, 1));
  // Two estimates of one landmark differ by about two detections' noise: the tolerance is
  // the gate's radius for the difference of two detections at range_max, along the worse axis.
  const double tolerance_m = std::sqrt(2.0 * config_.gate_accept_chi2 * sigma2);
  // Search again only when a landmark joined the widest window (a match needs it as a supporter).
  std::vector<int> recent_keys;
  for (const LandmarkTrack& t : tracks_)
    if (t.confirmed && travel_m_ - t.created_travel_m <= kWindows.back() * range_max_m_) recent_keys.push_back(t.key);
  const bool joined = std::any_of(recent_keys.begin(), recent_keys.end(), [&](int key) {
    return std::find(constellation_searched_.begin(), constellation_searched_.end(), key) == constellation_searched_.end();
  });
  if (!joined) return 0;
  constellation_searched_ = recent_keys;
  long tried = 0;
  std::optional<ConstellationMatch> match;
  double window_m = 0.0;
  std::vector<int> old, recent;
  std::vector<Eigen::Vector2d> old_xy, recent_xy;
  for (const double windows : kWindows) {
    window_m = windows * range_max_m_;
    old.clear();
    recent.clear();
    for (size_t j = 0; j < tracks_.size(); ++j) {
      const LandmarkTrack& t = tracks_[j];
      if (!t.confirmed) continue;
      if (travel_m_ - t.seen_travel_m > window_m) old.push_back(static_cast<int>(j));
      else if (travel_m_ - t.created_travel_m <= window_m) recent.push_back(static_cast<int>(j));
    }
    if (old.size() < 3) break;
    if (recent.size() < 3) continue;
    // The filter's heading has drifted from the old landmarks' frame since it last saw them
    // by no more than dead reckoning's would have (the motion model's heading variance summed
    // over the steps since the earliest of them was seen): the motions are bounded to its gate.
    double since_rad2 = 0.0;
    for (const int j : old) since_rad2 = std::max(since_rad2, heading_variance_rad2_ - tracks_[j].seen_heading_variance_rad2);
    old_xy.clear();
    recent_xy.clear();
    for (const int j : old) old_xy.push_back(state_.Landmark(j));
    for (const int j : recent) recent_xy.push_back(state_.Landmark(j));
    const ConstellationSettings settings{tolerance_m, 1.0 - gate_probability_, tried,
                                         std::sqrt(ChiSquareQuantile(gate_probability_, 1.0) * since_rad2),
                                         config_.constellation_max_hypotheses};
    match = MatchConstellation(old_xy, recent_xy, settings, &tried);
    if (match) break;
  }
  if (!match) return 0;
  if (LogMissedUnderMatch(*match, old, old_xy, tolerance_m, window_m) < std::log(1.0 - gate_probability_)) return 0;
  Record(t_s, "constellation_chance", match->chance);
  std::vector<bool> moved(tracks_.size(), true);  // the robot and the window's landmarks: all but the old
  for (const int j : old) moved[j] = false;
  MoveRigidly(state_, moved, match->T_old_recent, FitCovarianceAtRobot(*match, recent_xy, sigma2, state_.Pose()));
  std::vector<std::pair<int, int>> keys;  // (old, recent): indices shift as landmarks are removed
  for (const auto& [o, r] : match->pairs) keys.emplace_back(tracks_[old[o]].key, tracks_[recent[r]].key);
  auto index_of = [&](int key) {
    for (size_t j = 0; j < tracks_.size(); ++j)
      if (tracks_[j].key == key) return static_cast<int>(j);
    return -1;
  };
  int merged = 0;
  for (const auto& [old_key, recent_key] : keys) {
    if (SeenTogether(old_key, recent_key)) continue;
    const int a = index_of(old_key), b = index_of(recent_key);
    if (a >= 0 && b >= 0 && MergeTrackInto(a, b)) ++merged;
  }
  return merged;
}


double EkfSlam::LogMissedUnderMatch(const ConstellationMatch& match, const std::vector<int>& old,
                                    const std::vector<Eigen::Vector2d>& old_xy, double tolerance_m,
                                    double window_m) const {
  const SE2 T_inverse = match.T_old_recent.inverse();
  std::vector<bool> paired(old.size(), false), is_old(tracks_.size(), false);
  for (const auto& [o, r] : match.pairs) paired[o] = true;
  for (const int j : old) is_old[j] = true;
  std::vector<Eigen::Vector2d> window_xy;  // every landmark of the window, tentative ones too
  for (size_t j = 0; j < tracks_.size(); ++j)
    if (!is_old[j]) window_xy.push_back(state_.Landmark(static_cast<int>(j)));
  double log_missed = 0.0;
  for (size_t o = 0; o < old.size(); ++o) {
    if (paired[o]) continue;
    const Eigen::Vector2d q = T_inverse * old_xy[o];  // where the window would have mapped it
    if (std::any_of(window_xy.begin(), window_xy.end(), [&](const Eigen::Vector2d& m) { return (m - q).norm() <= tolerance_m; }))
      continue;
    for (auto it = scan_path_.rbegin(); it != scan_path_.rend() && travel_m_ - it->first <= window_m; ++it) {
      const Eigen::Vector2d zp = PredictObservation(it->second, q).z;
      if (ExpectedInView(zp)) log_missed += std::log1p(-std::min(DetectionProbability(detection_, zp.x()), 1.0 - 1e-12));
    }
  }
  return log_missed;
}

}  // namespace slambox
