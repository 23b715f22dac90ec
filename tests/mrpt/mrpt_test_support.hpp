#pragma once
// Shared fixtures for the MRPT module tests: a room with inner boxes for LIDAR, posts for
// landmarks, and the position error of an Estimate against the synthetic ground truth.
#include <gtest/gtest.h>

#include <Eigen/LU>

#include <cmath>
#include <map>

#include "core/slam_module.hpp"
#include "tests/support/synthetic_stream.hpp"

namespace slambox::testing {

inline void AddBox(World& w, Eigen::Vector2d lo, Eigen::Vector2d hi) {
  const Eigen::Vector2d c[4] = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
  for (int i = 0; i < 4; ++i) w.wall_segments.push_back({c[i], c[(i + 1) % 4]});
}

/// A room around the square path [0, side]² with two asymmetric boxes inside the loop.
inline World RoomWorld(double side_m) {
  World w;
  AddBox(w, {-2.0, -2.0}, {side_m + 2.0, side_m + 2.0});
  AddBox(w, {1.0, 1.0}, {2.0, 1.6});
  AddBox(w, {side_m - 2.2, side_m - 2.5}, {side_m - 1.0, side_m - 1.0});
  return w;
}

inline World PostWorld() {
  World w;
  const double xy[][2] = {{5, -2}, {12, 5}, {5, 12}, {-2, 5}, {2, 2}, {8, 8}, {8, 2}, {2, 8}, {-2, -2}, {12, 12}};
  int id = 0;
  for (const auto& p : xy) w.landmarks.push_back({id++, {p[0], p[1]}, 0.1});
  return w;
}

inline Stream LidarStream(double side_m, std::uint64_t seed, std::array<double, 4> alpha) {
  SyntheticOptions o;
  o.path = {{0, 0}, {side_m, 0}, {side_m, side_m}, {0, side_m}};
  o.seed = seed;
  o.sensors.odometry = OdometryConfig{50.0, alpha};
  LidarConfig lidar;
  lidar.beams = 360;
  lidar.range_max_m = 20.0;
  lidar.sigma_range_m = 0.01;
  o.sensors.lidar = lidar;
  return MakeSyntheticStream(o, RoomWorld(side_m));
}

inline Stream LandmarkStream(std::uint64_t seed, bool known_ids) {
  SyntheticOptions o;
  o.seed = seed;
  o.sensors.odometry = OdometryConfig{50.0, {0.05, 0.005, 0.05, 0.005}};
  LandmarkSensorConfig lm;
  lm.range_max_m = 8.0;
  lm.sigma_range_m = 0.05;
  lm.sigma_bearing_deg = 1.0;
  lm.known_ids = known_ids;
  o.sensors.landmarks = lm;
  return MakeSyntheticStream(o, PostWorld());
}

/// Position errors [m] of every trajectory pose against ground truth at the same time.
inline std::vector<double> PositionErrors(const Estimate& e, const Stream& s) {
  std::map<double, SE2> gt;
  for (const auto& p : s.groundtruth) gt[p.t_s] = p.pose;
  std::vector<double> err;
  for (const auto& p : e.trajectory) {
    const auto it = gt.find(p.t_s);
    EXPECT_NE(it, gt.end()) << "estimate time " << p.t_s << " is not a stream time";
    if (it != gt.end()) err.push_back((p.pose.translation() - it->second.translation()).norm());
  }
  return err;
}

inline double Rmse(const std::vector<double>& e) {
  double s = 0;
  for (double v : e) s += v * v;
  return e.empty() ? 0.0 : std::sqrt(s / e.size());
}

/// Dead reckoning's position RMSE at the same times as `e` (odometry composed from the start).
inline double DeadReckoningRmse(const Estimate& e, const Stream& s) {
  std::map<double, SE2> dr;
  SE2 pose = s.header.start_pose;
  dr[0.0] = pose;
  for (const auto& ev : s.events)
    if (const auto* o = std::get_if<OdometryEvent>(&ev)) dr[o->t_s] = pose = pose * o->delta;
  Estimate d;
  for (const auto& p : e.trajectory) d.trajectory.push_back({p.t_s, dr.at(p.t_s)});
  return Rmse(PositionErrors(d, s));
}

inline void ExpectIdenticalTrajectories(const Estimate& a, const Estimate& b) {
  ASSERT_EQ(a.trajectory.size(), b.trajectory.size());
  for (size_t i = 0; i < a.trajectory.size(); ++i) {
    EXPECT_EQ(a.trajectory[i].t_s, b.trajectory[i].t_s);
    EXPECT_EQ(a.trajectory[i].pose.x, b.trajectory[i].pose.x) << i;
    EXPECT_EQ(a.trajectory[i].pose.y, b.trajectory[i].pose.y) << i;
    EXPECT_EQ(a.trajectory[i].pose.theta, b.trajectory[i].pose.theta) << i;
  }
}

}  // namespace slambox::testing
