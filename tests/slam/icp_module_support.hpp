#pragma once
// Test support for the ICP modules: a synthetic ring corridor with pillars and a featureless
// rectangular corridor, their streams,
// and the position RMSE of an estimate against ground truth at shared timestamps.
#include <Eigen/Cholesky>
#include <array>
#include <cmath>
#include <map>

#include "core/slam_module.hpp"
#include "tests/support/accuracy_bound.hpp"
#include "tests/support/synthetic_scan.hpp"
#include "tests/support/synthetic_stream.hpp"

namespace slambox::testing {

/// Square ring corridor around (5, 5): outer walls at -2 and 12, an inner block 2..8,
/// a few pillars so straight legs are not perfectly degenerate.
inline World RingWorld() {
  World w;
  w.wall_segments = Polyline({{-2, -2}, {12, -2}, {12, 12}, {-2, 12}}, true);
  const auto inner = Polyline({{2, 2}, {8, 2}, {8, 8}, {2, 8}}, true);
  w.wall_segments.insert(w.wall_segments.end(), inner.begin(), inner.end());
  for (const Eigen::Vector2d& c : {Eigen::Vector2d(5, -1.2), Eigen::Vector2d(11, 5), Eigen::Vector2d(4, 11.2),
                                  Eigen::Vector2d(-1, 3)}) {
    const auto box = Polyline({c + Eigen::Vector2d(-0.2, -0.2), c + Eigen::Vector2d(0.2, -0.2),
                               c + Eigen::Vector2d(0.2, 0.2), c + Eigen::Vector2d(-0.2, 0.2)}, true);
    w.wall_segments.insert(w.wall_segments.end(), box.begin(), box.end());
  }
  return w;
}

inline Stream RingStream(std::uint64_t seed, int laps) {
  SyntheticOptions o;
  o.laps = laps;
  o.seed = seed;
  o.dt_s = 0.02;
  o.lidar_every_steps = 5;  // 10 Hz
  o.sensors.odometry = OdometryConfig{};
  o.sensors.odometry->alpha = {0.05, 0.005, 0.05, 0.005};
  LidarConfig lidar;
  lidar.beams = 360;
  lidar.sigma_range_m = 0.01;
  lidar.range_max_m = 30;
  o.sensors.lidar = lidar;
  return MakeSyntheticStream(o, RingWorld());
}

/// One lap around a featureless rectangular corridor: the robot drives the rectangle
/// (1.7, 1.7)-(51.3, 27.3) at 1.5 m/s between walls half_width_m either side of its path.
inline Stream RectangleCorridorStream(double half_width_m, std::uint64_t seed, const std::array<double, 4>& alpha,
                                      const LidarConfig& lidar) {
  const Eigen::Vector2d lo(1.7, 1.7), hi(51.3, 27.3), h(half_width_m, half_width_m);
  const Eigen::Vector2d outer_lo = lo - h, outer_hi = hi + h, inner_lo = lo + h, inner_hi = hi - h;
  World w;
  w.wall_segments = Polyline({outer_lo, {outer_hi.x(), outer_lo.y()}, outer_hi, {outer_lo.x(), outer_hi.y()}}, true);
  const auto inner = Polyline({inner_lo, {inner_hi.x(), inner_lo.y()}, inner_hi, {inner_lo.x(), inner_hi.y()}}, true);
  w.wall_segments.insert(w.wall_segments.end(), inner.begin(), inner.end());
  SyntheticOptions o;
  o.path = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
  o.speed_mps = 1.5;
  o.seed = seed;
  o.sensors.odometry = OdometryConfig{};
  o.sensors.odometry->alpha = alpha;
  o.sensors.lidar = lidar;
  return MakeSyntheticStream(o, w);
}

/// RMSE of the estimated positions at the ground-truth times they share (no alignment).
/// Calls f(estimate pose, true pose) for every estimated pose at a ground-truth time.
template <class F>
void ForEachMatchedPose(const Estimate& e, const Stream& s, F&& f) {
  std::map<double, SE2> gt;
  for (const auto& g : s.groundtruth) gt[g.t_s] = g.pose;
  for (const auto& p : e.trajectory)
    if (auto it = gt.find(p.t_s); it != gt.end()) f(p, it->second);
}

inline double PositionRmse(const Estimate& e, const Stream& s) {
  double sum = 0;
  int n = 0;
  ForEachMatchedPose(e, s, [&](const PoseEstimate& p, const SE2& truth) {
    sum += (p.pose.translation() - truth.translation()).squaredNorm();
    ++n;
  });
  return n ? std::sqrt(sum / n) : INFINITY;
}

/// Mean NEES (3 dof) of the poses that carry a covariance, at the ground-truth times they
/// share; poses with a singular covariance (the known start) are skipped. NaN if none.
inline double PoseAnees(const Estimate& e, const Stream& s) {
  double sum = 0;
  int n = 0;
  ForEachMatchedPose(e, s, [&](const PoseEstimate& p, const SE2& truth) {
    if (!p.has_covariance) return;
    const Eigen::LDLT<Eigen::Matrix3d> ldlt(p.covariance);
    if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 1e-14)) return;
    const Eigen::Vector3d d(p.pose.x - truth.x, p.pose.y - truth.y, NormalizeAngle(p.pose.theta - truth.theta));
    sum += d.dot(ldlt.solve(d));
    ++n;
  });
  return n ? sum / n : NAN;
}

inline Estimate RunModule(const ModuleInfo& info, const Stream& s, const ParamOverrides& overrides = {}) {
  auto module = info.create(overrides);
  return Replay(*module, s);
}

}  // namespace slambox::testing
