#include "datasets/landmark_log.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "core/error.hpp"
#include "core/limits.hpp"
#include "datasets/odometry_noise_fit.hpp"

namespace slambox {

namespace {

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(mid), v.end());
  return v[mid];
}

}  // namespace

Stream AssembleLandmarkLog(const LandmarkLog& log, const std::string& name, const LandmarkLogOptions& o) {
  if (!(o.pose_period_s > 0) || !(o.fov_deg > 0 && o.fov_deg <= 360))
    throw InputError(name, 0, "invalid import options (pose_period_s > 0, 0 < fov_deg <= 360)",
                     "check --pose-period-s / --fov-deg");
  if (o.range_max_m && !(*o.range_max_m > 0 && std::isfinite(*o.range_max_m)))
    throw InputError(name, 0, "invalid range max (must be a finite number > 0)", "check --range-max-m");
  if (log.increments.empty()) throw InputError(name, 0, "no odometry step", "the poses must form one chain 0, 1, 2, ...");
  const int last = static_cast<int>(log.increments.size());
  if (last * o.pose_period_s > limits::kMaxTimestampS) {
    std::ostringstream problem;
    problem << last << " steps of " << o.pose_period_s << " s end past the limit of " << limits::kMaxTimestampS
            << " s (core/limits.hpp)";
    throw InputError(name, 0, problem.str(), "give a smaller --pose-period-s");
  }
  if (!log.true_poses.empty() && log.true_poses.size() != log.increments.size() + 1)
    throw InputError(name, 0,
                     "ground truth for " + std::to_string(log.true_poses.size()) + " poses, the chain has " +
                         std::to_string(last + 1),
                     "give a true pose for every pose of the chain");
  std::map<int, std::vector<LandmarkObservation>> observed;  // pose -> observations
  std::vector<double> sigma_range, sigma_bearing;
  double range_max = 0.0;
  for (const LandmarkLog::Sighting& s : log.sightings) {
    if (s.pose < 0 || s.pose > last)
      throw InputError(name, 0, "a sighting names pose " + std::to_string(s.pose) + " outside the chain 0 .. " + std::to_string(last),
                       "check the pose indices");
    if (s.landmark < 0)
      throw InputError(name, 0, "a sighting from pose " + std::to_string(s.pose) + " names landmark id " +
                                    std::to_string(s.landmark), "landmark ids are >= 0 (a negative id means unknown in a stream)");
    const double x = s.point.x(), y = s.point.y(), r = std::hypot(x, y);
    if (!(r > 0)) throw InputError(name, 0, "a sighting from pose " + std::to_string(s.pose) + " at zero range", "remove it");
    observed[s.pose].push_back({r, std::atan2(y, x), s.landmark});
    range_max = std::max(range_max, r);
    // Polar covariance J P J^T with J = d(r, b)/d(x, y) = [[x, y] / r; [-y, x] / r^2].
    Eigen::Matrix2d J;
    J << x / r, y / r, -y / (r * r), x / (r * r);
    const Eigen::Matrix2d polar = J * s.covariance * J.transpose();
    sigma_range.push_back(std::sqrt(std::max(0.0, polar(0, 0))));
    sigma_bearing.push_back(std::sqrt(std::max(0.0, polar(1, 1))));
  }

  Stream s;
  s.header.scenario_name = std::filesystem::path(name).filename().string();
  s.header.scenario_yaml = std::string(kConvertedLogYamlPrefix) + o.description + " " + s.header.scenario_name +
                           (log.true_poses.empty() ? " (no ground truth)\n" : " (with its ground truth)\n");
  s.header.dt_s = o.pose_period_s;
  for (int k = 0; k <= last; ++k) {
    const double t = k * o.pose_period_s;
    if (k > 0) s.events.push_back(OdometryEvent{t, log.increments[static_cast<size_t>(k - 1)]});
    if (auto it = observed.find(k); it != observed.end()) s.events.push_back(LandmarkEvent{t, it->second});
  }
  s.header.duration_s = last * o.pose_period_s;
  if (!log.true_poses.empty()) {
    // Modules start at the true start (DESIGN.md); the chain's own frame is the truth's.
    s.header.start_pose = log.true_poses.front();
    for (size_t k = 0; k < log.true_poses.size(); ++k) s.groundtruth.push_back({k * o.pose_period_s, log.true_poses[k]});
  }
  for (const auto& [id, position] : log.true_landmarks) s.header.world.landmarks.push_back({id, position, 0.1});
  OdometryConfig odo;
  odo.rate_hz = 1.0 / o.pose_period_s;
  odo.alpha = o.odometry_alpha ? *o.odometry_alpha : FitOdometryAlpha(log.increments, log.increment_covariances).alpha;
  LandmarkSensorConfig lm;
  lm.rate_hz = 1.0 / o.pose_period_s;
  lm.range_max_m = o.range_max_m ? *o.range_max_m : std::ceil(range_max);
  lm.fov_deg = o.fov_deg;
  lm.sigma_range_m = Median(sigma_range);
  lm.sigma_bearing_deg = Median(sigma_bearing) * 180.0 / M_PI;
  lm.known_ids = true;
  lm.detection_prob_known = false;  // the file lists detections, not the scans that missed one
  s.header.sensors.odometry = odo;
  s.header.sensors.landmarks = lm;
  return s;
}

}  // namespace slambox
