#pragma once
// Merging duplicate landmarks in the smoother, jointly (issue 14, `forest`). After drift
// the EKF front end can map a revisited part of the map a second time; the smoothed
// graph is consistent where the front end was not, but each duplicate pair alone is far
// too uncertain to merge (its difference gate holds several other landmarks). Jointly it
// is not: once one pair is taken to be one point, the others' differences, conditioned on
// it, have small gates. For a hypothesis of pairs p_1 .. p_k, taken in order:
//   D_i = m_a - m_b of pair i, C_i = its covariance given D_1 = .. = D_{i-1} = 0
//         (the joint landmark Gaussian conditioned on each merge, slam/landmark_merge's
//         ConditionOnEqual: x' = x - K D, Sigma' = Sigma - K H Sigma, K = Sigma H^T C^-1),
//   accepted into the hypothesis if D_i^T C_i^-1 D_i < gate (the sum is the joint d^2),
//   mu_i = density * pi gate sqrt(det C_i): the landmarks other than a expected in b's gate,
//   P(every pair of the hypothesis is two distinct landmarks) = prod_i min(1, mu_i).
// Hypotheses grow greedily (the gated pair with the smallest conditional gate area next,
// each landmark in one pair) from every candidate pair as the seed. Growth takes any pair
// inside the gate, and a pair whose gate holds other landmarks (mu_i >= 1) costs the test
// below nothing, so each grown hypothesis then drops, worst first, every pair it explains
// worse than two landmarks would (its likelihood factor given all the others below 1,
// slam/pairing_likelihood.hpp). Of the hypotheses whose chance of being all wrong is below
// the gate's own miss probability, the largest is taken (JCBB's criterion), ties by the
// likelihood against "no merges", N(D; 0, C) / density^k (with k equal, N(D; 0, C): the
// joint d^2 and the log det C that d^2 alone ignores). The likelihood does not rank
// hypotheses of different size: C is linearized before any merge, and along a lap the
// true pairs far from the seed get conditional d^2 of 20-30 (`forest` seed 65: the right
// 31-pair hypothesis scores log 150, a 28-pair one with a wrong pair log 161). Two
// landmarks seen in one scan are two landmarks and never a pair. The density is the
// map's own (landmarks over the area of their convex hull), the threshold the merge
// gate's: no new constant.
#include <Eigen/Core>
#include <set>
#include <utility>
#include <vector>

namespace slambox {

struct JointLandmarks {
  std::vector<int> keys;       ///< landmark keys, in the order of the stacked state
  Eigen::VectorXd mean;        ///< 2 per landmark [m]
  Eigen::MatrixXd covariance;  ///< joint, 2n x 2n [m^2]
};

/// The ambiguity test of a merge (and of a split, slam/reobservation_split.hpp).
struct MergeSearchSettings {
  double gate_chi2 = 9.21;          ///< [chi2, 2 dof] a pair's (conditional) gate
  double fake_probability = 0.01;   ///< accept a hypothesis less likely than this to be all wrong (1 - the gate's probability)
  double density_per_m2 = 0.0;      ///< [1/m^2] landmarks per area (MapDensity)
};

/// Landmarks per m^2: their number over the area of their convex hull (0 below 3).
double MapDensity(const Eigen::VectorXd& mean);

/// The pairs (kept key, removed key; the kept one is the smaller key) of the best jointly
/// compatible hypothesis, or none. `seen_together`: key pairs (smaller first) observed in one scan.
std::vector<std::pair<int, int>> FindJointMerges(const JointLandmarks& landmarks,
                                                 const std::set<std::pair<int, int>>& seen_together,
                                                 const MergeSearchSettings& settings);

/// D^T C^-1 D of the stacked differences D = (m_keep - m_remove, ..) of `pairs` (keys), C
/// their joint covariance: what merging them all raises the graph's chi2 by in the
/// linearized model (conditioning on D = 0). Infinity if C is not positive definite.
double PairsDifferenceChi2(const JointLandmarks& landmarks, const std::vector<std::pair<int, int>>& pairs);

/// The front end's own pairings that the smoother leaves standing: of `proposals` (a split-off
/// segment's key, the key of the landmark the front end paired it with; see
/// slam/reobservation_split.hpp), those whose difference d^2 is below `keep_chi2` while
/// neither landmark has any other inside `gate_chi2` (among those not seen with it). The
/// split asks the smoother to re-decide a re-observation, not to assume it wrong: a pairing
/// it does not reject and nothing rivals is kept even where its gate's expected count (mu)
/// is too large for FindJointMerges to propose it. `keep_chi2` is the front end's own
/// rejection gate (gate_new_chi2: beyond it the EKF itself starts a new landmark), wider
/// than the merge gate: at the merge gate 1 % of the true pairs, of which a run has
/// dozens, would be left as duplicates. Returns (kept, removed) pairs, smaller key kept,
/// greedily by d^2, each landmark in at most one pair.
std::vector<std::pair<int, int>> UnchallengedPairings(const JointLandmarks& landmarks,
                                                      const std::set<std::pair<int, int>>& seen_together,
                                                      const std::vector<std::pair<int, int>>& proposals,
                                                      double gate_chi2, double keep_chi2);

}  // namespace slambox
