#include "slam/held_pairings.hpp"

#include <algorithm>
#include <cmath>

#include "core/chi_square.hpp"
#include "slam/data_association.hpp"

namespace slambox {

const EnumNames<HoldEvidence>& HoldEvidenceNames() {
  static const EnumNames<HoldEvidence> names = {{HoldEvidence::kDistinctLandmarks, "landmarks"},
                                                {HoldEvidence::kLandmarksAndTracks, "tracks"},
                                                {HoldEvidence::kRepeatedScans, "scans"}};
  return names;
}

std::vector<bool> HoldUncertainPairings(const EkfSlamState& state, const std::vector<Eigen::Vector2d>& z,
                                        const Eigen::Matrix2d& R, const std::vector<int>& keys,
                                        TrackEvidence& tracks, const HoldTest& test,
                                        std::vector<int>& target, HeldStreak& streak) {
  const bool repeats = test.evidence == HoldEvidence::kRepeatedScans;
  std::vector<bool> held(state.NumLandmarks(), false);
  HeldStreak now;
  std::vector<std::pair<int, int>> pairs;
  for (size_t i = 0; i < z.size(); ++i)
    if (target[i] >= 0) pairs.emplace_back(static_cast<int>(i), target[i]);
  if (!pairs.empty()) {
    const auto S = ConditionalInnovationCovariances(JointInnovationOf(state, z, R, pairs).S);
    const double log_allowed = std::log(1.0 - ChiSquareCdf(test.gate_chi2, 2.0));
    for (size_t q = 0; q < pairs.size(); ++q) {
      const auto [i, j] = pairs[q];
      const double log_mu =
          std::log(std::min(1.0, ExpectedFalseInGate(S[q], z[i].x(), test.gate_chi2, test.clutter_density_per_m2)));
      std::optional<double>& track = tracks[j];
      const bool tracked = test.evidence == HoldEvidence::kLandmarksAndTracks && track.has_value();
      double log_p = log_mu + (tracked ? *track : 0.0);
      for (const auto& [key, log_fake] : streak)
        if (repeats ? key == keys[j] : key != keys[j]) log_p += log_fake;
      if (log_p <= log_allowed) {
        if (tracked) *track = 0.0;  // used: it places the landmark, the next repeats start anew
        continue;
      }
      if (tracked) *track += log_mu;
      now[keys[j]] = repeats ? log_p : log_mu;
      target[i] = Association::kDiscard;
      held[j] = true;
    }
  }
  if (repeats || now.empty()) streak = std::move(now);
  else
    for (const auto& [key, log_fake] : now) streak[key] = log_fake;
  return held;
}

}  // namespace slambox
