// `EkfSlam`'s merges of two landmarks found to be one (unknown ids): duplicates that became
// statistically identical near the robot (MergeDuplicates), and the pairs of a constellation
// match (slam/ekf_slam_constellation.cpp); both through MergeTrackInto.
#include <algorithm>
#include <tuple>
#include <vector>

#include "core/chi_square.hpp"
#include "slam/ekf_slam.hpp"
#include "slam/landmark_merge.hpp"

namespace slambox {

int EkfSlam::MergeDuplicates(bool certain_only, bool* uncertain_found) {
  if (!(config_.merge_probability > 0.0)) return 0;
  const double gate = ChiSquareQuantile(config_.merge_probability, 2.0);
  const Eigen::Vector2d robot = state_.Pose().translation();
  int merged = 0;
  // Only around the robot: a duplicate becomes identical to its twin when the loop
  // closes, i.e. while the robot sees them (this bounds the work to the local map).
  for (bool again = true; again;) {
    again = false;
    std::vector<int> near;
    for (int j = 0; j < state_.NumLandmarks(); ++j)
      if ((state_.Landmark(j) - robot).norm() < range_max_m_) near.push_back(j);
    // The most similar pair first: a landmark can have two twins in its gate, one of them
    // a new tree next to it (forest seed 218: tree 12's twin at d^2 2.5 and tree 8 at 8.0;
    // merging the first found took tree 8 and the filter never recovered).
    std::vector<std::tuple<double, int, int>> pairs;  // (d^2, a, b), a < b: a is the older landmark and is kept
    for (size_t p = 0; p < near.size(); ++p)
      for (size_t q = p + 1; q < near.size(); ++q) {
        const int a = near[p], b = near[q];
        if (SeenTogether(tracks_[a].key, tracks_[b].key)) continue;
        const PointDifference difference = DifferenceOf(state_.mean, state_.covariance, 3 + 2 * a, 3 + 2 * b);
        if (!(difference.d2 < gate)) continue;
        if (certain_only && ExpectedInGate(difference.C, gate, FakeDensity()) > 1.0 - gate_probability_) {
          if (uncertain_found != nullptr) *uncertain_found = true;
          continue;
        }
        pairs.emplace_back(difference.d2, a, b);
      }
    std::sort(pairs.begin(), pairs.end());
    for (size_t k = 0; k < pairs.size() && !again; ++k) {
      const auto [d2, a, b] = pairs[k];
      if (!MergeTrackInto(a, b)) continue;
      ++merged;
      again = true;
    }
  }
  return merged;
}

bool EkfSlam::MergeTrackInto(int a, int b) {
  if (!MergeLandmarks(state_, a, b)) return false;
  LandmarkTrack& keep = tracks_[a];
  const LandmarkTrack& gone = tracks_[b];
  keep.sightings += gone.sightings;
  keep.existence += gone.existence;
  keep.expected_detections += gone.expected_detections;
  keep.detected_scans += gone.detected_scans;
  keep.log_ratio += gone.log_ratio;  // independent trials of one landmark
  keep.confirmed = keep.confirmed || gone.confirmed || ReadyToConfirm(keep);
  keep.seen_travel_m = std::max(keep.seen_travel_m, gone.seen_travel_m);
  keep.seen_heading_variance_rad2 = std::max(keep.seen_heading_variance_rad2, gone.seen_heading_variance_rad2);
  keep.created_travel_m = std::min(keep.created_travel_m, gone.created_travel_m);
  merged_into_[gone.key] = keep.key;
  // What was seen together with the removed landmark was seen together with the kept one.
  for (const auto& [k1, k2] : std::vector<std::pair<int, int>>(co_observed_.begin(), co_observed_.end())) {
    if (k1 == gone.key && k2 != keep.key) co_observed_.insert(std::minmax(keep.key, k2));
    if (k2 == gone.key && k1 != keep.key) co_observed_.insert(std::minmax(keep.key, k1));
  }
  tracks_.erase(tracks_.begin() + b);
  return true;
}

}  // namespace slambox
