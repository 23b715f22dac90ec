#include "slam/reobservation_split.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "slam/data_association.hpp"
#include "slam/range_bearing.hpp"

namespace slambox {

namespace {

bool InView(const SE2& pose, const Eigen::Vector2d& m, const SensorFootprint& f) {
  const Eigen::Vector2d z = PredictObservation(pose, m).z;
  return z.x() <= f.range_max_m && std::abs(z.y()) <= f.half_fov_rad;
}

}  // namespace

DeadReckonedDifference DeadReckoned(const LandmarkGraph& g, int k1, int k, const Eigen::Vector2d& m,
                                    const Eigen::Vector2d& z) {
  const int from = std::min(k1, k), to = std::max(k1, k);
  SE2 T;  // from -> to by odometry, covariance over (x, y, theta)
  Eigen::Matrix3d Sigma = Eigen::Matrix3d::Zero();
  for (int j = from; j < to; ++j) {
    const OdometryConstraint& o = g.odometry.at(j);
    Sigma = ComposeCovariance(T, Sigma, o.T_from_to, o.covariance);
    T = T * o.T_from_to;
  }
  const Eigen::Vector2d p1 = g.poses.at(k1).inverse() * m;  // the landmark in k1's frame
  const double c = std::cos(T.theta), s = std::sin(T.theta);
  Eigen::Matrix<double, 2, 3> J;  // d/d(t, theta) of the landmark in k's frame
  Eigen::Vector2d predicted;
  if (k1 <= k) {  // T = k in k1's frame: R^T (p1 - t)
    const Eigen::Vector2d p = p1 - T.translation();
    predicted = RotationMatrix(T.theta).transpose() * p;
    J << -c, -s, -s * p.x() + c * p.y(), s, -c, -c * p.x() - s * p.y();
  } else {  // T = k1 in k's frame: R p1 + t
    predicted = T * p1;
    J << 1, 0, -s * p1.x() - c * p1.y(), 0, 1, c * p1.x() - s * p1.y();
  }
  const LandmarkInitialization detected = InverseObservation(SE2(), z);  // (r cos b, r sin b), G = d/d(r, b)
  const Eigen::Matrix2d& G = detected.J_landmark_z;
  DeadReckonedDifference d;
  d.difference = predicted - detected.landmark;
  d.C = J * Sigma * J.transpose() + 2.0 * G * g.observation_covariance * G.transpose();
  return d;
}

double ReobservationAmbiguity(const LandmarkGraph& g, int k1, int k2, const Eigen::Vector2d& m,
                              const Eigen::Vector2d& z, const MergeSearchSettings& test) {
  return ExpectedInGate(DeadReckoned(g, k1, k2, m, z).C, test.gate_chi2, test.density_per_m2);
}

ReobservationSplit SplitAtReobservations(LandmarkGraph& graph, const SensorFootprint& footprint, const MergeSearchSettings& test,
                                         int first_free_key) {
  ReobservationSplit split;
  std::map<int, int> last_keyframe;  // landmark key (original) -> keyframe of its last observation
  std::map<int, int> current_key;    // landmark key (original) -> the key of its current segment
  std::map<int, std::pair<Eigen::Vector2d, int>> sums;  // new key -> sum of inverse observations, count
  int next_key = first_free_key;
  for (RangeBearingConstraint& o : graph.observations) {
    const auto m = graph.landmarks.find(o.landmark);
    if (m == graph.landmarks.end()) continue;
    const int original = o.landmark;
    const auto last = last_keyframe.find(original);
    if (last != last_keyframe.end() && o.keyframe > last->second + 1) {
      bool left_view = false;
      for (int k = last->second + 1; k < o.keyframe && !left_view; ++k)
        left_view = !InView(graph.poses[k], m->second, footprint);
      if (left_view && ReobservationAmbiguity(graph, last->second, o.keyframe, m->second, o.z, test) >= test.fake_probability) {
        current_key[original] = next_key;
        split.segments[original].push_back({o.keyframe, next_key});
        ++next_key;
      }
    }
    last_keyframe[original] = o.keyframe;
    const auto c = current_key.find(original);
    if (c == current_key.end()) continue;
    o.landmark = c->second;
    auto& [sum, count] = sums[o.landmark];
    if (count == 0) sum.setZero();
    sum += InverseObservation(graph.poses[o.keyframe], o.z).landmark;
    ++count;
  }
  for (const auto& [key, s] : sums) split.guesses[key] = s.first / s.second;
  return split;
}

int SegmentKey(const ReobservationSplit& split, int key, int keyframe) {
  const auto it = split.segments.find(key);
  if (it == split.segments.end()) return key;
  int segment = key;
  for (const LandmarkSegment& s : it->second)
    if (s.first_keyframe <= keyframe) segment = s.key;
  return segment;
}

}  // namespace slambox
