#include "slam/keyframe_decimation.hpp"

#include <algorithm>
#include <stdexcept>

namespace slambox {

int DecimationStride(int last_keyframe, int max_keyframes) {
  return max_keyframes > 0 ? (last_keyframe + max_keyframes) / max_keyframes : 1;
}

DecimatedGraph DecimateKeyframes(const LandmarkGraph& full, int stride) {
  if (stride < 1) throw std::invalid_argument("DecimateKeyframes: stride must be at least 1");
  const int n = static_cast<int>(full.poses.size());
  if (static_cast<int>(full.odometry.size()) != std::max(0, n - 1))
    throw std::invalid_argument("DecimateKeyframes: the odometry must chain every keyframe to the next");
  DecimatedGraph d;
  std::vector<int> index_of(static_cast<size_t>(n), -1);  // full keyframe -> kept index
  for (int k = 0; k < n; ++k)
    if (k % stride == 0 || k == n - 1) {
      index_of[static_cast<size_t>(k)] = static_cast<int>(d.kept.size());
      d.kept.push_back(k);
      d.graph.poses.push_back(full.poses[static_cast<size_t>(k)]);
    }
  for (size_t i = 1; i < d.kept.size(); ++i) {
    OdometryConstraint c{static_cast<int>(i) - 1, SE2(), Eigen::Matrix3d::Zero()};
    for (int k = d.kept[i - 1]; k < d.kept[i]; ++k) {
      const OdometryConstraint& o = full.odometry[static_cast<size_t>(k)];
      if (o.from != k) throw std::invalid_argument("DecimateKeyframes: odometry constraints out of keyframe order");
      c.covariance = ComposeCovariance(c.T_from_to, c.covariance, o.T_from_to, o.covariance);
      c.T_from_to = c.T_from_to * o.T_from_to;
    }
    d.graph.odometry.push_back(c);
  }
  for (const RangeBearingConstraint& o : full.observations) {
    const int i = index_of.at(static_cast<size_t>(o.keyframe));
    if (i >= 0) d.graph.observations.push_back({i, o.landmark, o.z});
  }
  d.graph.landmarks = full.landmarks;
  d.graph.observation_covariance = full.observation_covariance;
  return d;
}

void SpreadDecimatedSolution(const DecimatedGraph& d, LandmarkGraph& full) {
  for (size_t i = 0; i < d.kept.size(); ++i) {
    const auto first = static_cast<size_t>(d.kept[i]);
    const size_t end = i + 1 < d.kept.size() ? static_cast<size_t>(d.kept[i + 1]) : first + 1;
    const SE2 correction = d.graph.poses[i] * full.poses[first].inverse();  // old kept pose -> new
    for (size_t k = first + 1; k < end; ++k) full.poses[k] = correction * full.poses[k];
    full.poses[first] = d.graph.poses[i];
  }
  for (const auto& [key, m] : d.graph.landmarks) full.landmarks[key] = m;
}

}  // namespace slambox
