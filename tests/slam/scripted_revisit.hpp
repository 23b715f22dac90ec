#pragma once
// The scripted revisit of the constellation tests (ekf_slam_constellation_test.cpp,
// fastslam_constellation_test.cpp): twelve trees mapped at the start, a 60 m drive without
// scans (30 m out and back, as the odometry says), then the same trees seen from
// `true_return` instead of the start; and a longer drive with a drift that trees mapped on
// the way carry (DriftStream). Noise-free detections, small odometry alpha.
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "core/estimate.hpp"
#include "core/stream.hpp"

namespace slambox::scripted_revisit {

inline const std::vector<Eigen::Vector2d> kTrees = {{3, 1},  {6, -2},  {-4, 3}, {-2, -6}, {7, 4},  {-6, -1},
                                                   {1, 7},  {4, -7},  {-8, 6}, {9, -1},  {-3, -9}, {-9, -5}};

inline std::vector<LandmarkObservation> SeenFrom(const SE2& pose, const std::vector<Eigen::Vector2d>& trees) {
  std::vector<LandmarkObservation> z;
  for (const Eigen::Vector2d& m : trees) {
    const Eigen::Vector2d local = pose.inverse() * m;
    z.push_back({local.norm(), std::atan2(local.y(), local.x()), -1});
  }
  return z;
}

inline std::vector<LandmarkObservation> SeenFrom(const SE2& pose) { return SeenFrom(pose, kTrees); }

/// The sensors: small odometry alpha, a 20 m, 360 degree detector without clutter.
inline Stream EmptyStream() {
  Stream s;
  s.header.seed = 7;
  s.header.sensors.odometry = OdometryConfig{.rate_hz = 50, .alpha = {1e-5, 1e-5, 1e-4, 1e-5}};
  s.header.sensors.landmarks = LandmarkSensorConfig{.rate_hz = 5, .range_max_m = 20, .fov_deg = 360,
                                                    .sigma_range_m = 0.05, .sigma_bearing_deg = 0.5,
                                                    .known_ids = false, .clutter_per_scan = 0.0};
  return s;
}

/// `start_scans` scans at the start, the drive, then `return_scans` scans from `true_return`.
inline Stream RevisitStream(const SE2& true_return, int start_scans, int return_scans) {
  Stream s = EmptyStream();
  double t = 0.0;
  for (int k = 0; k < start_scans; ++k) s.events.push_back(LandmarkEvent{t += 0.2, SeenFrom(SE2())});
  for (int leg = 0; leg < 2; ++leg) {
    for (int k = 0; k < 60; ++k) s.events.push_back(OdometryEvent{t += 0.1, SE2(0.5, 0, 0)});
    s.events.push_back(OdometryEvent{t += 0.1, SE2(0, 0, M_PI - 1e-9)});
  }
  for (int k = 0; k < return_scans; ++k) {
    s.events.push_back(OdometryEvent{t += 0.1, SE2(0, 0, 0)});
    s.events.push_back(LandmarkEvent{t, SeenFrom(true_return)});
  }
  return s;
}

/// Six trees about 50 m out (only the drift test's middle scans see them).
inline const std::vector<Eigen::Vector2d> kFarTrees = {{47, 3}, {52, -4}, {55, 2}, {45, -2}, {50, 6}, {57, -5}};

/// A drift the filter maps through: `scans` scans of kTrees at the start, 60 m out, a turn
/// that truly turns `turn_error.theta` more than the odometry says and slips by
/// (`turn_error.x`, `turn_error.y`), 10 m back, `scans` scans of kFarTrees (mapped with the
/// turn's error), 50 m back, then `scans` + 1 scans of kTrees from where the robot truly is
/// (`*true_return`). The far trees are old at the return (seen 50 m before, beyond the 40 m
/// window) and carry the same drift as the window.
inline Stream DriftStream(const SE2& turn_error, int scans, SE2* true_return) {
  Stream s = EmptyStream();
  double t = 0.0;
  SE2 truth;
  auto drive = [&](int steps) {
    for (int k = 0; k < steps; ++k) {
      s.events.push_back(OdometryEvent{t += 0.1, SE2(0.5, 0, 0)});
      truth = truth * SE2(0.5, 0, 0);
    }
  };
  auto scans_of = [&](int n, const std::vector<Eigen::Vector2d>& trees) {
    for (int k = 0; k < n; ++k) {
      s.events.push_back(OdometryEvent{t += 0.1, SE2(0, 0, 0)});
      s.events.push_back(LandmarkEvent{t, SeenFrom(truth, trees)});
    }
  };
  for (int k = 0; k < scans; ++k) s.events.push_back(LandmarkEvent{t += 0.2, SeenFrom(truth, kTrees)});
  drive(120);
  s.events.push_back(OdometryEvent{t += 0.1, SE2(0, 0, M_PI - 1e-9)});
  truth = truth * turn_error * SE2(0, 0, M_PI - 1e-9);
  drive(20);
  scans_of(scans, kFarTrees);
  drive(100);
  scans_of(scans + 1, kTrees);
  *true_return = truth;
  return s;
}

/// The sum of a diagnostic series (0 if the module never recorded it).
inline double Sum(const Estimate& e, const std::string& name) {
  const auto it = e.diagnostics.find(name);
  if (it == e.diagnostics.end()) return 0.0;
  return std::accumulate(it->second.begin(), it->second.end(), 0.0,
                         [](double a, const auto& sample) { return a + sample.second; });
}

}  // namespace slambox::scripted_revisit
