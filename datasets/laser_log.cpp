#include "datasets/laser_log.hpp"

#include <algorithm>
#include <cmath>
#include <climits>
#include <filesystem>

#include "core/error.hpp"

namespace slambox {

namespace {
constexpr double kDefaultRangeMaxM = 80.0;
}  // namespace

Stream AssembleLaserLog(LaserLog log, const std::string& name, const LaserLogOptions& o, double log_range_max_m) {
  if (log.scans.empty() && log.landmarks.empty())
    throw InputError(name, 0, "no laser scan or landmark observation: nothing to convert",
                     "give a log with laser scans (or range-bearing observations)");
  if (log.odometry.empty())
    throw InputError(name, 0, "no odometry in the log", "give a log with odometry (poses or increments)");

  double range_max = o.range_max_m;
  if (range_max == 0 && log_range_max_m > 0) range_max = log_range_max_m;
  if (range_max == 0 && !log.scans.empty() && log.scans.front().range_max_m > 0) range_max = log.scans.front().range_max_m;
  if (range_max == 0) range_max = kDefaultRangeMaxM;

  const SE2 offset = log.T_robot_laser;
  const SE2 offset_inv = offset.inverse();
  const auto by_time = [](const auto& a, const auto& b) { return a.ts < b.ts; };
  std::stable_sort(log.odometry.begin(), log.odometry.end(), by_time);
  std::stable_sort(log.scans.begin(), log.scans.end(), by_time);
  std::stable_sort(log.landmarks.begin(), log.landmarks.end(), by_time);
  double t0 = log.odometry.front().ts;
  if (!log.scans.empty()) t0 = std::min(t0, log.scans.front().ts);
  if (!log.landmarks.empty()) t0 = std::min(t0, log.landmarks.front().ts);
  const auto step = [&](double ts) { return std::llround((ts - t0) / o.dt_s); };

  Stream s;
  s.header.scenario_name = std::filesystem::path(name).filename().string();
  s.header.scenario_yaml = std::string(kConvertedLogYamlPrefix) + "the " + log.format + " " + s.header.scenario_name + " (no ground truth)\n";
  s.header.dt_s = o.dt_s;
  s.header.time_origin_s = t0;  // the log's clock at t = 0: relation files use that clock
  s.header.start_pose = log.odometry.front().pose * offset;
  const bool laser_at_origin = offset.x == 0.0 && offset.y == 0.0 && offset.theta == 0.0;
  size_t k = 1, j = 0, l = 0;
  SE2 previous = log.odometry.front().pose;
  const auto observation_step = [&] {  // the next scan's or landmark message's step, scans first on ties
    const long long scan = j < log.scans.size() ? step(log.scans[j].ts) : LLONG_MAX;
    const long long landmarks = l < log.landmarks.size() ? step(log.landmarks[l].ts) : LLONG_MAX;
    return std::min(scan, landmarks);
  };
  while (k < log.odometry.size() || j < log.scans.size() || l < log.landmarks.size()) {
    const bool observations_left = j < log.scans.size() || l < log.landmarks.size();
    const bool odometry_next = k < log.odometry.size() && (!observations_left || step(log.odometry[k].ts) <= observation_step());
    if (odometry_next) {
      const LaserLog::Odometry& p = log.odometry[k++];
      const OdometryEvent e{static_cast<double>(step(p.ts)) * o.dt_s, offset_inv * Between(previous, p.pose) * offset};
      previous = p.pose;
      auto* last = s.events.empty() ? nullptr : std::get_if<OdometryEvent>(&s.events.back());
      if (e.t_s == 0.0 && s.events.empty()) s.header.start_pose = s.header.start_pose * e.delta;
      else if (last && last->t_s == e.t_s) last->delta = last->delta * e.delta;
      else s.events.push_back(e);
      continue;
    }
    if (j < log.scans.size() && step(log.scans[j].ts) == observation_step()) {
      const LaserLog::Scan& in = log.scans[j++];
      LaserScanEvent e;
      e.t_s = static_cast<double>(step(in.ts)) * o.dt_s;
      e.angle_min_rad = in.angle_min_rad;
      e.angle_increment_rad = in.angle_increment_rad;
      e.range_min_m = o.range_min_m;
      e.range_max_m = range_max;
      for (size_t i = 0; i < in.ranges_m.size(); ++i) {
        const double r = in.ranges_m[i];
        // Without flags a return at the limit is CARMEN's "no return"; a flagged-valid one
        // (rawlogs) may lie on it (MRPT's and slambox's simulated scans clamp to it).
        const bool hit = in.valid.empty() ? r >= o.range_min_m && r < range_max
                                          : in.valid[i] != 0 && r >= o.range_min_m && r <= range_max;
        e.ranges_m.push_back(hit ? r : range_max);
        e.valid.push_back(hit ? 1 : 0);
      }
      s.events.push_back(std::move(e));
      continue;
    }
    const LaserLog::Landmarks& in = log.landmarks[l++];
    LandmarkEvent e;
    e.t_s = static_cast<double>(step(in.ts)) * o.dt_s;
    for (LandmarkObservation obs : in.observations) {
      if (!laser_at_origin) {  // from the robot origin to the laser (the stream's robot frame)
        const Eigen::Vector2d p = offset_inv * Eigen::Vector2d(obs.range_m * std::cos(obs.bearing_rad),
                                                               obs.range_m * std::sin(obs.bearing_rad));
        obs.range_m = p.norm();
        obs.bearing_rad = std::atan2(p.y(), p.x());
      }
      e.observations.push_back(obs);
    }
    s.events.push_back(std::move(e));
  }
  s.header.duration_s = EventTime(s.events.back());
  const double duration = std::max(s.header.duration_s, o.dt_s);
  OdometryConfig odometry;
  const auto odometry_events = std::count_if(s.events.begin(), s.events.end(),
                                             [](const SensorEvent& e) { return std::holds_alternative<OdometryEvent>(e); });
  odometry.rate_hz = static_cast<double>(odometry_events) / duration;
  odometry.alpha = o.odometry_alpha;
  s.header.sensors.odometry = odometry;
  if (!log.scans.empty()) {
    LidarConfig lidar;
    const LaserLog::Scan& first = log.scans.front();
    lidar.rate_hz = static_cast<double>(log.scans.size()) / duration;
    lidar.beams = static_cast<int>(first.ranges_m.size());
    lidar.fov_deg = std::abs(first.angle_increment_rad) * (lidar.beams - (lidar.beams % 2 == 1 ? 1 : 0)) * 180.0 / M_PI;
    lidar.range_min_m = o.range_min_m;
    lidar.range_max_m = range_max;
    lidar.sigma_range_m = o.sigma_range_m;
    s.header.sensors.lidar = lidar;
  }
  if (!log.landmarks.empty()) {
    LandmarkSensorConfig unsaid;  // a log without a sensor block says nothing of its P_D either
    unsaid.detection_prob_known = false;
    LandmarkSensorConfig landmarks = log.landmark_sensor.value_or(unsaid);
    landmarks.rate_hz = static_cast<double>(log.landmarks.size()) / duration;
    s.header.sensors.landmarks = landmarks;
  }
  return s;
}

}  // namespace slambox
