#include "slam/leftover_association.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <map>
#include <set>

#include "slam/data_association.hpp"
#include "slam/range_bearing.hpp"
#include "slam/reobservation_split.hpp"

namespace slambox {
namespace {

/// The keyframe of `sorted` closest to k (ties: the earlier).
int Nearest(const std::vector<int>& sorted, int k) {
  const auto it = std::lower_bound(sorted.begin(), sorted.end(), k);
  if (it == sorted.end()) return sorted.back();
  if (it == sorted.begin() || *it - k < k - *std::prev(it)) return *it;
  return *std::prev(it);
}

}  // namespace

std::vector<int> AssociateLeftovers(const LandmarkGraph& graph, const LandmarkGraphSolution& s,
                                    const std::vector<LeftoverDetection>& detections, const LeftoverSettings& settings) {
  std::vector<int> joined(detections.size(), -1);
  if (!s.covariance_ok) return joined;
  std::map<int, std::vector<int>> observers;  // landmark -> keyframes observing it, sorted
  std::set<std::pair<int, int>> observed;     // (keyframe, landmark)
  for (const RangeBearingConstraint& o : graph.observations) {
    if (!graph.landmarks.count(o.landmark)) continue;
    observers[o.landmark].push_back(o.keyframe);
    observed.insert({o.keyframe, o.landmark});
  }
  for (auto& [key, k] : observers) std::sort(k.begin(), k.end());
  std::vector<Eigen::Vector2d> points;  // each detection in its keyframe's frame
  for (const LeftoverDetection& d : detections) points.push_back(InverseObservation(SE2(), d.z).landmark);
  std::map<std::pair<int, int>, int> choosers;  // (keyframe, landmark) -> leftover detections choosing it
  for (size_t i = 0; i < detections.size(); ++i) {
    const LeftoverDetection& d = detections[i];
    const SE2& pose = graph.poses.at(static_cast<size_t>(d.keyframe));
    const Eigen::Matrix3d& P_pose = s.pose_covariances.at(static_cast<size_t>(d.keyframe));
    int candidate = -1, in_gate = 0;
    Eigen::Matrix2d C_candidate;
    for (const auto& [key, m] : graph.landmarks) {
      const auto P_m = s.landmark_covariances.find(key);
      const auto seen_by = observers.find(key);
      if (P_m == s.landmark_covariances.end() || seen_by == observers.end()) continue;
      const ObservationPrediction p = PredictObservation(pose, m);
      const Eigen::Matrix2d S = p.J_z_pose * P_pose * p.J_z_pose.transpose() +
                                p.J_z_landmark * P_m->second * p.J_z_landmark.transpose() + graph.observation_covariance;
      const Eigen::Vector2d nu = Innovation(d.z, p.z);
      if (nu.dot(S.inverse() * nu) >= settings.gate_chi2) continue;  // 1: loose
      const DeadReckonedDifference r = DeadReckoned(graph, Nearest(seen_by->second, d.keyframe), d.keyframe, m, d.z);
      if (r.difference.dot(r.C.inverse() * r.difference) >= settings.gate_chi2) continue;  // 2
      ++in_gate;
      candidate = key;
      C_candidate = r.C;
    }
    // One landmark in the gate, established (seen from two keyframes: slam/graphslam drops a
    // split-off segment seen from one as no evidence of a landmark) and not seen here already.
    if (in_gate != 1 || observed.count({d.keyframe, candidate})) continue;
    const std::vector<int>& seen = observers.at(candidate);
    if (seen.front() == seen.back()) continue;
    // Fakes expected in the gate: at the declared density, or as often as leftovers of the
    // run fell there relative to the sensor, if more often (a stream that declares less
    // clutter than it has, or clutter that is not uniform over the footprint).
    const Eigen::Matrix2d C_inv = C_candidate.inverse();
    int nearby = 0;
    for (size_t j = 0; j < detections.size(); ++j)
      if (j != i && (points[j] - points[i]).dot(C_inv * (points[j] - points[i])) < settings.gate_chi2) ++nearby;
    const double mu = std::max(ExpectedInGate(C_candidate, settings.gate_chi2, settings.fake_density_per_m2),
                               nearby / static_cast<double>(graph.poses.size()));
    if (mu >= settings.fake_probability) continue;
    joined[i] = candidate;
    ++choosers[{d.keyframe, candidate}];
  }
  for (size_t i = 0; i < detections.size(); ++i)  // two detections of one scan are two landmarks
    if (joined[i] >= 0 && choosers[{detections[i].keyframe, joined[i]}] > 1) joined[i] = -1;
  return joined;
}

}  // namespace slambox
