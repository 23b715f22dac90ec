#pragma once
// Test support: small synthetic Streams without Box2D, for unit and accuracy tests of
// SLAM modules and the evaluator. A robot drives a closed polygon path at constant speed;
// odometry is sampled from Thrun's model, landmark observations are range-bearing with
// Gaussian noise, LIDAR scans are exact ray-segment intersections plus range noise.
// Deterministic for a given seed; one generator per noise source.
#include <cmath>
#include <random>
#include <vector>

#include "core/odometry_model.hpp"
#include "core/stream.hpp"

namespace slambox::testing {

struct SyntheticOptions {
  std::vector<Eigen::Vector2d> path = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};  ///< closed loop
  int laps = 1;
  double speed_mps = 1.0;
  double turn_rate_rps = 1.0;
  double dt_s = 0.02;  ///< one odometry event per step
  std::uint64_t seed = 1;
  SensorSuite sensors;  ///< odometry required; landmarks / lidar optional
  int landmark_every_steps = 5;
  int lidar_every_steps = 5;
};

namespace detail {
inline void TrueMotion(const SyntheticOptions& o, std::vector<StampedPose>& gt) {
  SE2 pose(o.path[0].x(), o.path[0].y(), 0.0);
  double t = 0.0;
  int step = 0;
  gt.push_back({0.0, pose});
  for (int lap = 0; lap < o.laps; ++lap) {
    for (size_t k = 1; k <= o.path.size(); ++k) {
      const Eigen::Vector2d goal = o.path[k % o.path.size()];
      const double heading = std::atan2(goal.y() - pose.y, goal.x() - pose.x);
      while (std::abs(NormalizeAngle(heading - pose.theta)) > 1e-9) {  // turn in place
        const double dth = NormalizeAngle(heading - pose.theta);
        const double w = std::copysign(std::min(std::abs(dth), o.turn_rate_rps * o.dt_s), dth);
        pose = SE2(pose.x, pose.y, pose.theta + w);
        t = ++step * o.dt_s;
        gt.push_back({t, pose});
      }
      double remaining = (goal - pose.translation()).norm();
      while (remaining > 1e-9) {
        const double d = std::min(remaining, o.speed_mps * o.dt_s);
        pose = pose * SE2(d, 0.0, 0.0);
        remaining -= d;
        t = ++step * o.dt_s;
        gt.push_back({t, pose});
      }
    }
  }
}
}  // namespace detail

/// Builds the stream. `world` supplies landmarks (for landmark observations) and wall
/// segments (for LIDAR).
inline Stream MakeSyntheticStream(const SyntheticOptions& o, const World& world) {
  Stream s;
  s.header.scenario_name = "synthetic";
  s.header.seed = o.seed;
  s.header.dt_s = o.dt_s;
  s.header.sensors = o.sensors;
  s.header.world = world;
  detail::TrueMotion(o, s.groundtruth);
  s.header.start_pose = s.groundtruth.front().pose;
  s.header.duration_s = s.groundtruth.back().t_s;
  std::mt19937_64 odo_rng(o.seed * 3 + 1), lm_rng(o.seed * 3 + 2), lidar_rng(o.seed * 3 + 3);
  std::normal_distribution<double> n01(0.0, 1.0);
  for (size_t i = 1; i < s.groundtruth.size(); ++i) {
    const SE2& prev = s.groundtruth[i - 1].pose;
    const SE2& now = s.groundtruth[i].pose;
    const double t = s.groundtruth[i].t_s;
    if (o.sensors.odometry) {
      OdometryIncrement u = Decompose(Between(prev, now));
      const Eigen::Matrix3d M = IncrementCovariance(u, o.sensors.odometry->alpha);
      u.rot1 += std::sqrt(M(0, 0)) * n01(odo_rng);
      u.trans += std::sqrt(M(1, 1)) * n01(odo_rng);
      u.rot2 += std::sqrt(M(2, 2)) * n01(odo_rng);
      s.events.push_back(OdometryEvent{t, Compose(u)});
    }
    if (o.sensors.landmarks && i % o.landmark_every_steps == 0) {
      const auto& cfg = *o.sensors.landmarks;
      LandmarkEvent ev{t, {}};
      for (const auto& lm : world.landmarks) {
        const Eigen::Vector2d d = lm.position - now.translation();
        const double r = d.norm();
        const double b = NormalizeAngle(std::atan2(d.y(), d.x()) - now.theta);
        if (r > cfg.range_max_m || std::abs(b) > cfg.fov_deg * M_PI / 360.0) continue;
        LandmarkObservation obs;
        obs.range_m = r + cfg.sigma_range_m * n01(lm_rng);
        obs.bearing_rad = NormalizeAngle(b + cfg.sigma_bearing_deg * M_PI / 180.0 * n01(lm_rng));
        obs.id = cfg.known_ids ? lm.id : -1;
        ev.observations.push_back(obs);
      }
      s.events.push_back(ev);
    }
    if (o.sensors.lidar && i % o.lidar_every_steps == 0) {
      const auto& cfg = *o.sensors.lidar;
      LaserScanEvent scan;
      scan.t_s = t;
      const double fov = cfg.fov_deg * M_PI / 180.0;
      scan.angle_increment_rad = fov / cfg.beams;
      scan.angle_min_rad = -fov / 2;
      scan.range_min_m = cfg.range_min_m;
      scan.range_max_m = cfg.range_max_m;
      for (int b = 0; b < cfg.beams; ++b) {
        const double a = now.theta + scan.angle_min_rad + b * scan.angle_increment_rad;
        const Eigen::Vector2d dir(std::cos(a), std::sin(a)), o2 = now.translation();
        double best = cfg.range_max_m;
        for (const auto& seg : world.wall_segments) {  // solve o2 + r dir = a + u (b - a)
          const Eigen::Vector2d e = seg.b - seg.a;
          const double den = dir.x() * (-e.y()) - dir.y() * (-e.x());
          if (std::abs(den) < 1e-12) continue;
          const Eigen::Vector2d rhs = seg.a - o2;
          const double r = (rhs.x() * (-e.y()) - rhs.y() * (-e.x())) / den;
          const double u = (dir.x() * rhs.y() - dir.y() * rhs.x()) / den;
          if (r > 0 && u >= 0 && u <= 1 && r < best) best = r;
        }
        const bool hit = best < cfg.range_max_m && best >= cfg.range_min_m;
        scan.ranges_m.push_back(hit ? best + cfg.sigma_range_m * n01(lidar_rng) : cfg.range_max_m);
        scan.valid.push_back(hit ? 1 : 0);
      }
      s.events.push_back(scan);
    }
  }
  return s;
}

}  // namespace slambox::testing
