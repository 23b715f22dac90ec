#pragma once
// Relative pose error exactly as evo defines it (metrics.RPE, filters.id_pairs_from_delta):
// for a pair (i, j), E_ij = (Q_i^-1 Q_j)^-1 (P_i^-1 P_j) with Q the ground truth and P the
// estimate; the translation error is |t(E_ij)| [m], the rotation error |angle(E_ij)| [deg].
// Pairs are chosen on the estimate (evo's default; pairs_from_reference = the reference):
// - frames:  consecutive (0,d),(d,2d),...; all pairs (i, i+d).
// - metres:  consecutive: the path length is accumulated from pose 0 and an index is
//            recorded (and the sum reset) each time it reaches delta; pairs join
//            successive recorded indices (so the first pair starts after delta metres).
//            All pairs: for each i, the j > i whose path length from i is nearest to
//            delta, kept when within tol = rel_delta_tol * delta.
// - degrees: consecutive: |relative heading change| accumulated step by step, a pair
//            closes each time the sum reaches delta. All pairs: every j > i whose
//            direct relative angle lies in [delta - tol, delta + tol].
#include <string>
#include <utility>
#include <vector>

#include "core/se2.hpp"

namespace slambox {

enum class DeltaUnit { kFrames, kMeters, kDegrees };

struct RpeOptions {
  double delta = 1.0;                  ///< in `unit` (frames: an integer)
  DeltaUnit unit = DeltaUnit::kMeters;
  bool all_pairs = false;
  double rel_delta_tol = 0.1;          ///< all-pairs tolerance, relative to delta (evo 0.1)
  bool pairs_from_reference = false;   ///< choose pairs on ground truth instead of the estimate
};

using IndexPair = std::pair<int, int>;

/// evo's pair selection on `poses`. Empty when no pair qualifies.
std::vector<IndexPair> SelectPairs(const std::vector<SE2>& poses, const RpeOptions& options);

/// E_ij for one pair, computed as R(dtheta_gt)^T (t_est_rel - t_gt_rel) and
/// wrap(theta_est_rel - theta_gt_rel), which equals the composition above and is exactly
/// the identity for identical relative motions.
SE2 RelativePoseError(const SE2& Q_i, const SE2& Q_j, const SE2& P_i, const SE2& P_j);

struct RpeResult {
  std::vector<IndexPair> pairs;
  std::vector<double> translation_m;
  std::vector<double> rotation_deg;  ///< >= 0
};

RpeResult ComputeRpe(const std::vector<SE2>& gt, const std::vector<SE2>& est, const RpeOptions& options);

/// "m", "f" / "frames", "d" / "deg" / "degrees"; false for anything else.
bool ParseDeltaUnit(const std::string& text, DeltaUnit& unit);
std::string DeltaUnitName(DeltaUnit unit);  ///< "m", "f", "d"

}  // namespace slambox
