#pragma once
// Test support for landmark SLAM: a small synthetic landmark world around the default
// 10 m square path of synthetic_stream.hpp, and trajectory error / NEES against the
// stream's ground truth (matched by time: every estimate time is a simulator step).
#include <Eigen/Cholesky>
#include <cmath>
#include <vector>

#include "core/estimate.hpp"
#include "tests/support/synthetic_stream.hpp"

namespace slambox::testing {

/// Landmarks on two rings (inside and outside the square path), ids 0..n-1.
inline World LandmarkWorld() {
  World w;
  int id = 0;
  for (double a : {-2.5, 5.0, 12.5})
    for (double b : {-2.5, 12.5}) {
      w.landmarks.push_back({id++, {a, b}, 0.1});
      w.landmarks.push_back({id++, {b, a + 0.7}, 0.1});
    }
  for (double a : {2.5, 7.5})
    for (double b : {2.5, 7.5}) w.landmarks.push_back({id++, {a, b}, 0.1});
  return w;
}

inline SyntheticOptions LandmarkOptions(std::uint64_t seed, int laps = 2, bool known_ids = true) {
  SyntheticOptions o;
  o.seed = seed;
  o.laps = laps;
  o.sensors.odometry = OdometryConfig{};
  LandmarkSensorConfig lm;
  lm.range_max_m = 7.0;
  lm.known_ids = known_ids;
  o.sensors.landmarks = lm;
  return o;
}

inline const SE2& TruePoseAt(const Stream& s, double t_s) {
  const auto i = static_cast<size_t>(std::llround(t_s / s.header.dt_s));
  return s.groundtruth.at(i).pose;
}

/// Root mean square position error over the trajectory [m], no alignment.
inline double AteRmse(const Stream& s, const Estimate& e) {
  double sum = 0.0;
  for (const auto& p : e.trajectory) sum += (p.pose.translation() - TruePoseAt(s, p.t_s).translation()).squaredNorm();
  return std::sqrt(sum / e.trajectory.size());
}

/// Pose NEES at each trajectory entry with a non-singular covariance (3 dof).
inline std::vector<double> PoseNees(const Stream& s, const Estimate& e) {
  std::vector<double> nees;
  for (const auto& p : e.trajectory) {
    if (!p.has_covariance || p.covariance.determinant() < 1e-30) continue;
    const SE2& T = TruePoseAt(s, p.t_s);
    const Eigen::Vector3d err(p.pose.x - T.x, p.pose.y - T.y, NormalizeAngle(p.pose.theta - T.theta));
    nees.push_back(err.dot(p.covariance.ldlt().solve(err)));
  }
  return nees;
}

/// For each estimated landmark, the distance to the nearest true landmark [m].
inline std::vector<double> NearestTrueDistance(const World& w, const Estimate& e) {
  std::vector<double> d;
  for (const auto& l : e.landmarks) {
    double best = 1e9;
    for (const auto& t : w.landmarks) best = std::min(best, (t.position - l.position).norm());
    d.push_back(best);
  }
  return d;
}

}  // namespace slambox::testing
