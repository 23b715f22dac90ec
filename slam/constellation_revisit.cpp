#include "slam/constellation_revisit.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/chi_square.hpp"
#include "slam/range_bearing.hpp"

namespace slambox {

namespace {
/// [range_max] the windows of travel tried, narrowest first.
constexpr std::array<double, 3> kWindows = {2.0, 4.0, 8.0};
}  // namespace

double RevisitTolerance(const Eigen::Matrix2d& R, double range_max_m, double gate_chi2) {
  const double sigma2 = std::max(R(0, 0), range_max_m * range_max_m * R(1, 1));
  return std::sqrt(2.0 * gate_chi2 * sigma2);
}

double RevisitWidestWindow(double range_max_m) { return kWindows.back() * range_max_m; }

bool RevisitWorthSearching(std::span<const RevisitLandmark> confirmed, std::span<const int> keys,
                           const RevisitSettings& settings, std::vector<int>& searched) {
  std::vector<int> recent_keys;
  for (size_t j = 0; j < confirmed.size(); ++j)
    if (settings.travel_m - confirmed[j].created_travel_m <= RevisitWidestWindow(settings.range_max_m))
      recent_keys.push_back(keys[j]);
  const bool joined = std::any_of(recent_keys.begin(), recent_keys.end(), [&](int key) {
    return std::find(searched.begin(), searched.end(), key) == searched.end();
  });
  if (joined) searched = std::move(recent_keys);
  return joined;
}

std::optional<Revisit> FindRevisit(std::span<const RevisitLandmark> confirmed, const RevisitSettings& settings) {
  long tried = 0;
  Revisit revisit;
  std::vector<Eigen::Vector2d> old_xy, recent_xy;
  for (const double windows : kWindows) {
    const double window_m = windows * settings.range_max_m;
    revisit.old.clear();
    revisit.recent.clear();
    for (size_t j = 0; j < confirmed.size(); ++j) {
      if (settings.travel_m - confirmed[j].seen_travel_m > window_m) revisit.old.push_back(static_cast<int>(j));
      else if (settings.travel_m - confirmed[j].created_travel_m <= window_m) revisit.recent.push_back(static_cast<int>(j));
    }
    if (revisit.old.size() < 3) break;
    if (revisit.recent.size() < 3) continue;
    double since_rad2 = 0.0, since_m = 0.0;  // prior (1): dead reckoning's heading variance and travel since the earliest old sighting
    for (const int j : revisit.old) {
      since_rad2 = std::max(since_rad2, settings.heading_variance_rad2 - confirmed[j].seen_heading_variance_rad2);
      since_m = std::max(since_m, settings.travel_m - confirmed[j].seen_travel_m);
    }
    old_xy.clear();
    recent_xy.clear();
    for (const int j : revisit.old) old_xy.push_back(confirmed[j].xy);
    for (const int j : revisit.recent) recent_xy.push_back(confirmed[j].xy);
    const ConstellationSettings match_settings{
        settings.tolerance_m,
        1.0 - settings.gate_probability,
        tried,
        std::sqrt(ChiSquareQuantile(settings.gate_probability, 1.0) * since_rad2),
        settings.max_hypotheses,
        std::max(settings.tolerance_m, std::sqrt(ChiSquareQuantile(settings.gate_probability, 2.0) * since_rad2) * since_m),
        settings.robot_xy};
    std::optional<ConstellationMatch> match = MatchConstellation(old_xy, recent_xy, match_settings, &tried);
    if (match) {
      revisit.match = std::move(*match);
      revisit.window_m = window_m;
      return revisit;
    }
  }
  return std::nullopt;
}

double RevisitShare(double v_rad2, double paired_rad2, double now_rad2) {
  if (!(now_rad2 > paired_rad2)) return 0.0;
  return std::clamp((v_rad2 - paired_rad2) / (now_rad2 - paired_rad2), 0.0, 1.0);
}

std::vector<double> RevisitShares(const Revisit& revisit, std::span<const RevisitLandmark> confirmed,
                                  const RevisitSettings& settings) {
  std::vector<double> shares(revisit.old.size(), 0.0);
  std::vector<bool> paired(revisit.old.size(), false);
  double paired_rad2 = 0.0;
  for (const auto& [o, r] : revisit.match.pairs) {
    paired[o] = true;
    paired_rad2 = std::max(paired_rad2, confirmed[revisit.old[o]].seen_heading_variance_rad2);
  }
  for (size_t o = 0; o < revisit.old.size(); ++o)
    if (!paired[o])
      shares[o] =
          RevisitShare(confirmed[revisit.old[o]].seen_heading_variance_rad2, paired_rad2, settings.heading_variance_rad2);
  return shares;
}

SE2 PartOfMotion(const SE2& T, double share) {
  if (share >= 1.0) return T;  // exactly, not through Log and Exp
  if (share <= 0.0) return SE2();
  return Exp(share * Log(T));
}

double LogMissedUnderRevisit(const Revisit& revisit, std::span<const RevisitLandmark> confirmed,
                             std::span<const Eigen::Vector2d> window_xy, std::span<const SE2> scan_poses,
                             double tolerance_m, std::span<const double> shares,
                             const std::function<double(const Eigen::Vector2d&)>& detection_in_view) {
  const SE2& T = revisit.match.T_old_recent;
  const SE2 T_inverse = T.inverse();
  std::vector<bool> paired(revisit.old.size(), false);
  for (const auto& [o, r] : revisit.match.pairs) paired[o] = true;
  double log_missed = 0.0;
  for (size_t o = 0; o < revisit.old.size(); ++o) {
    if (paired[o]) continue;
    const RevisitLandmark& old = confirmed[revisit.old[o]];
    const double share = shares.empty() ? 0.0 : shares[o];
    // Where the window would have mapped it: moved by its share of T into the old map's frame,
    // then into the window's.
    const Eigen::Vector2d q = T_inverse * (PartOfMotion(T, share) * old.xy);
    if (std::any_of(window_xy.begin(), window_xy.end(), [&](const Eigen::Vector2d& m) { return (m - q).norm() <= tolerance_m; }))
      continue;
    for (const SE2& pose : scan_poses) {
      const double p_detect = detection_in_view(PredictObservation(pose, q).z);
      if (p_detect > 0.0) log_missed += std::log1p(-std::min(p_detect, 1.0 - 1e-12));
    }
  }
  return log_missed;
}

}  // namespace slambox
