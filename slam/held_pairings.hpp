#pragma once
// Holding a scan's pairings that one fake detection could have made (issue 14, `forest`).
// A pairing is only as good as its gate is small. Its gate, conditioned on the scan's
// other pairings (ConditionalInnovationCovariances), holds an expected mu fake detections
// (ExpectedFalseInGate with the configured clutter density); a large mu is the lone
// re-observation of an old landmark after drift: a loop closure on one detection. It is
// held (not used, its landmark not counted as missed) while the probability that it is a
// fake is above the gate's own miss probability 1 - P[chi2(2) < gate]. Fakes of distinct
// landmarks are independent, so the pairings of n distinct landmarks held in consecutive
// scans are all fakes with probability mu_1 ... mu_n (HoldEvidence::kDistinctLandmarks).
// A repeat of one pairing is independent only if the fake is clutter (drawn anew every
// scan): a tree never mapped that sits in an old landmark's gate repeats too (forest
// seed 0, slam/README_landmark_slam.md), so repeats count only with kRepeatedScans, or
// (kLandmarksAndTracks, the default) while the landmark's track continues: since its
// creation, or since a pairing that placed it after its track had ended, the robot drifted
// less than one detection's gate from where it last placed the landmark and missed it no
// likelier than its gate would (slam/ekf_slam.hpp). Less than a gate of drift separates
// such a repeat from the sighting that placed the landmark: the object that made it is
// still in its gate, and a tree there is that one, not an unmapped one met after a loop.
// The track's held repeats count until one is used (which ends them, as a scan that holds
// nothing ends the streak). Without this a lone landmark in view (a sparse park, a narrow
// detector) was held scan after scan and never confirmed (held-out park lm1_4).
// Several such pairings in one jointly compatible scan pin each other down (small
// conditional gates) and pass at once.
#include <Eigen/Core>
#include <map>
#include <optional>
#include <vector>

#include "core/params.hpp"
#include "slam/ekf_slam_filter.hpp"

namespace slambox {

/// What lets a held pairing through: held pairings of distinct landmarks in consecutive
/// scans; those and the repeats of a pairing that continues its landmark's track; or
/// repeats of the same pairing in consecutive scans (the first rule).
enum class HoldEvidence { kDistinctLandmarks, kLandmarksAndTracks, kRepeatedScans };
/// landmarks, tracks, scans.
const EnumNames<HoldEvidence>& HoldEvidenceNames();

struct HoldTest {
  double gate_chi2 = 9.21;              ///< [chi2, 2 dof] the individual gate; its miss probability is the threshold
  double clutter_density_per_m2 = 0.0;  ///< [1/m^2] the sensor's clutter_per_scan over its footprint
  HoldEvidence evidence = HoldEvidence::kLandmarksAndTracks;
};

/// The streak of held pairings in consecutive scans: landmark key -> log of the
/// probability that its pairing is a fake (the product over its repeats where they count).
using HeldStreak = std::map<int, double>;

/// Per landmark index: the log of the probability that the pairings its continuing track
/// held since it last used one were all fakes (0 after a used one, and at the track's
/// start), or nullopt where no track continues.
using TrackEvidence = std::vector<std::optional<double>>;

/// Discards (sets to Association::kDiscard) the pairings of `target` (per observation z,
/// a landmark index of `state` or negative) that may be fakes; `keys`: per landmark index
/// its key; `tracks`: the evidence of the continuing tracks (kLandmarksAndTracks), updated.
/// Returns per landmark index whether its pairing was held; updates `streak` (it ends with
/// a scan that does not hold the landmark, kDistinctLandmarks: that holds nothing).
std::vector<bool> HoldUncertainPairings(const EkfSlamState& state, const std::vector<Eigen::Vector2d>& z,
                                        const Eigen::Matrix2d& R, const std::vector<int>& keys,
                                        TrackEvidence& tracks, const HoldTest& test,
                                        std::vector<int>& target, HeldStreak& streak);

}  // namespace slambox
