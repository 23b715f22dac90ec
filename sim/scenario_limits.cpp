// Size estimate of a scenario's stream and the checks of core/limits.hpp that need the
// whole scenario (stream memory, geometry-check work). Per-value limits (beams,
// duration_s, coordinates, list lengths) are ranges checked where the value is parsed.
#include "sim/scenario_limits.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "core/limits.hpp"
#include "core/stream.hpp"
#include "sim/scenario_yaml.hpp"

namespace slambox {
namespace {

std::uint64_t FiringsPer(double rate_hz, double dt_s, std::uint64_t steps) {
  if (!(rate_hz > 0.0)) return 0;
  const double every = std::max(1.0, std::round(1.0 / (rate_hz * dt_s)));
  return static_cast<std::uint64_t>(static_cast<double>(steps) / every) + 1;
}

std::string Megabytes(std::uint64_t bytes) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(1);
  s << static_cast<double>(bytes) / 1e6 << " MB";
  return s.str();
}

}  // namespace

StreamSizeEstimate EstimateStreamSize(const Scenario& scenario, const SimulationOptions& options) {
  StreamSizeEstimate e;
  e.duration_s = scenario.duration_s > 0.0 ? scenario.duration_s : options.max_duration_s;
  const double dt = options.dt_s;
  e.steps = static_cast<std::uint64_t>(std::ceil(e.duration_s / dt)) + 1;
  const SensorSuite& s = scenario.sensors;
  std::uint64_t scans = 0, sightings = 0;
  if (s.odometry) e.events += FiringsPer(s.odometry->rate_hz, dt, e.steps);
  if (s.gyro) e.events += FiringsPer(s.gyro->rate_hz, dt, e.steps);
  if (s.lidar) {
    scans = FiringsPer(s.lidar->rate_hz, dt, e.steps);
    e.events += scans;
    e.laser_readings = scans * static_cast<std::uint64_t>(s.lidar->beams);
  }
  if (s.landmarks) {
    sightings = FiringsPer(s.landmarks->rate_hz, dt, e.steps);
    e.events += sightings;
    const double per_scan = static_cast<double>(scenario.landmarks.size()) + std::ceil(s.landmarks->clutter_per_scan);
    e.landmark_observations = sightings * static_cast<std::uint64_t>(per_scan);
  }
  e.bytes = e.events * sizeof(SensorEvent) + e.laser_readings * (sizeof(double) + 1) +
            e.landmark_observations * sizeof(LandmarkObservation) + e.steps * sizeof(StampedPose);
  return e;
}

std::string DescribeStreamSize(const StreamSizeEstimate& e) {
  std::ostringstream s;
  s << "stream estimate (upper bound, " << e.duration_s << " s simulated): " << e.steps << " steps, " << e.events
    << " sensor events, " << e.laser_readings << " laser readings, " << e.landmark_observations
    << " landmark observations, ~" << Megabytes(e.bytes) << " of memory (limit " << Megabytes(limits::kMaxStreamBytes)
    << ")";
  return s.str();
}

namespace scenario_detail {

void CheckScenarioSize(const Scenario& s) {
  const StreamSizeEstimate e = EstimateStreamSize(s);
  if (e.bytes > limits::kMaxStreamBytes)
    throw InputError(s.source, 0,
                     "the scenario asks for a stream of ~" + Megabytes(e.bytes) + " (" + DescribeStreamSize(e) +
                         "), over the limit of " + Megabytes(limits::kMaxStreamBytes),
                     "lower duration_s, sensors.*.rate_hz, sensors.lidar.beams or the number of landmarks");
  // The geometry check tests every robot/mover leg against every obstacle.
  std::uint64_t obstacles = s.landmarks.size(), legs = s.robot.path.size() + 3;
  for (const WallSpec& w : s.walls) obstacles += std::max<std::size_t>(w.points.size(), 4);
  for (const MoverSpec& m : s.movers) legs += m.path.size();
  if (legs * obstacles > limits::kMaxGeometryPairs)
    throw InputError(s.source, 0,
                     std::to_string(legs) + " path legs x " + std::to_string(obstacles) +
                         " wall edges and posts = " + std::to_string(legs * obstacles) +
                         " geometry checks, over the limit of " + std::to_string(limits::kMaxGeometryPairs),
                     "use fewer waypoints (robot.path, movers' paths) or fewer wall points and posts");
}

}  // namespace scenario_detail
}  // namespace slambox
