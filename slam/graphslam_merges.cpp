// `GraphSlam`'s merges in the smoother (unknown ids): rounds of joint merges under the
// solved graph's marginals (slam/smoother_merges.hpp), each kept only if the re-solved
// nonlinear graph agrees with the linearization it was decided on (slam/graphslam.hpp).
#include <set>

#include "core/chi_square.hpp"
#include "slam/graphslam.hpp"
#include "slam/smoother_merges.hpp"

namespace slambox {

namespace {
/// The graph's landmarks stacked in key order (no covariance).
JointLandmarks Stacked(const std::map<int, Eigen::Vector2d>& landmarks) {
  JointLandmarks joint;
  joint.mean.resize(2 * static_cast<long>(landmarks.size()));
  for (const auto& [key, m] : landmarks) {
    joint.mean.segment<2>(2 * static_cast<long>(joint.keys.size())) = m;
    joint.keys.push_back(key);
  }
  return joint;
}
}  // namespace

MergeSearchSettings GraphSlam::AmbiguityTest() const {
  const double p = config_.frontend.merge_probability;
  return {ChiSquareQuantile(p, 2), 1.0 - p, MapDensity(Stacked(graph_.landmarks).mean)};
}

bool GraphSlam::MergesInSmoother() const {
  const double p = config_.frontend.merge_probability;
  return !known_ids_ && config_.smoother_merges && config_.compute_covariance && p > 0 && p < 1;
}

int GraphSlam::MergeInSmoother(LandmarkGraphSolution& s) {
  int merges = 0;
  // Each round merges at least one pair or rejects at least one, so this ends.
  for (;;) {
    if (!s.covariance_ok || s.landmark_joint_covariance.size() == 0) break;
    JointLandmarks joint = Stacked(graph_.landmarks);
    joint.covariance = s.landmark_joint_covariance;
    // Landmarks observed at one keyframe are distinct, and so are pairs the re-solved
    // graph refused (MergeIfTheGraphAgrees).
    std::set<std::pair<int, int>> together = rejected_merges_;
    for (size_t i = 0; i < graph_.observations.size();) {
      size_t end = i;
      while (end < graph_.observations.size() && graph_.observations[end].keyframe == graph_.observations[i].keyframe) ++end;
      for (size_t u = i; u < end; ++u)
        for (size_t v = u + 1; v < end; ++v)
          together.insert(std::minmax(graph_.observations[u].landmark, graph_.observations[v].landmark));
      i = end;
    }
    const MergeSearchSettings round = AmbiguityTest();
    std::vector<std::pair<int, int>> pairs = FindJointMerges(joint, together, round);
    if (pairs.empty()) {
      // Nothing left to decide jointly: the front end's pairings the smoother confirms.
      std::set<std::pair<int, int>> proposals;
      for (const auto& [original, segments] : split_.segments)
        for (const LandmarkSegment& segment : segments) proposals.insert({GraphKey(segment.key), GraphKey(original)});
      for (const auto& pair : rejected_merges_) proposals.erase(pair), proposals.erase({pair.second, pair.first});
      pairs = UnchallengedPairings(joint, together, {proposals.begin(), proposals.end()}, round.gate_chi2,
                                   std::max(round.gate_chi2, config_.frontend.gate_new_chi2));
    }
    if (pairs.empty()) break;
    merges += MergeIfTheGraphAgrees(pairs, s);
  }
  return merges;
}

int GraphSlam::MergeIfTheGraphAgrees(const std::vector<std::pair<int, int>>& proposed, LandmarkGraphSolution& s) {
  // After a first half merged, a key of the second may have been merged away.
  std::vector<std::pair<int, int>> pairs;
  for (const auto& [keep, remove] : proposed)
    if (GraphKey(keep) != GraphKey(remove)) pairs.push_back(std::minmax(GraphKey(keep), GraphKey(remove)));
  JointLandmarks joint = Stacked(graph_.landmarks);
  joint.covariance = s.landmark_joint_covariance;
  if (pairs.empty() || !s.covariance_ok || joint.covariance.rows() != joint.mean.size()) return 0;
  // The merges were decided on the linearized marginals, where merging the set raises the
  // graph's chi2 by exactly d^2 = D^T C^-1 D of its stacked differences. The re-solved
  // graph's rise above that is what the linearization did not see; more than the set's own
  // gate (the merge_probability quantile of chi2(2k)) and the nonlinear graph disagrees (a
  // correction too large for the linearization, a wrong hypothesis it hid): the set is
  // undone and halved, each half tried on its own, a single pair that fails never
  // proposed again. Issue 14, random park lm2_0: one 52-pair round took the re-solved
  // chi2 from 1.07e4 to 1.75e6 and turned the trajectory by 90 degrees.
  // A set whose solution puts more landmarks on keyframes that observe them (the
  // range-bearing factor's singularity, where SolveLandmarkGraph leaves the observation out
  // and so lowers chi2) folded the graph: refused too (held-out park lm3_10: one such round
  // drew nine keyframes 1.8 m apart within 0.1 m of each other, 47 observations left out).
  const LandmarkGraph graph_before = graph_;
  const std::map<int, Eigen::Vector2d> landmarks_before = solved_landmarks_;
  const double linear_chi2 = PairsDifferenceChi2(joint, pairs);
  for (const auto& [keep, remove] : pairs) merged_into_[remove] = keep;
  LandmarkGraphSolution next = Solve({.joint_landmarks = true});
  const double k = static_cast<double>(pairs.size());
  const double allowed = linear_chi2 + ChiSquareQuantile(config_.frontend.merge_probability, 2.0 * k);
  if (next.usable && next.observations_left_out <= s.observations_left_out && next.chi2_final - s.chi2_final <= allowed) {
    s = std::move(next);
    return static_cast<int>(pairs.size());
  }
  for (const auto& [keep, remove] : pairs) merged_into_.erase(remove);
  graph_ = graph_before;
  solved_landmarks_ = landmarks_before;
  if (pairs.size() == 1) {
    rejected_merges_.insert(pairs[0]);  // (smaller, larger) already
    return 0;
  }
  const auto middle = pairs.begin() + static_cast<long>(pairs.size() / 2);
  const int first = MergeIfTheGraphAgrees({pairs.begin(), middle}, s);
  return first + MergeIfTheGraphAgrees({middle, pairs.end()}, s);
}

}  // namespace slambox
