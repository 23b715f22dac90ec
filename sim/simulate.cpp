// The simulation loop: fixed steps of dt_s; ground truth at every step; each sensor fires
// every round(1 / (rate_hz dt_s)) steps, in the order odometry, gyro, lidar, landmarks.
#include "sim/simulate.hpp"

#include <cmath>
#include <optional>
#include <sstream>

#include "core/error.hpp"
#include "core/version.hpp"
#include "sim/box2d_world.hpp"
#include "sim/gyro_sensor.hpp"
#include "sim/landmark_sensor.hpp"
#include "sim/lidar.hpp"
#include "sim/odometry_sensor.hpp"
#include "sim/waypoint_controller.hpp"

namespace slambox {

namespace {
long StepsPerEvent(double rate_hz, double dt_s) { return std::max(1L, std::lround(1.0 / (rate_hz * dt_s))); }

SE2 ToPose(const PoseSpec& p) { return SE2(p.x, p.y, p.theta_deg * M_PI / 180.0); }

std::string Xy(const Eigen::Vector2d& p) {
  std::ostringstream s;
  s.precision(4);
  s << "[" << p.x() << ", " << p.y() << "]";
  return s.str();
}

/// Generous time to reach a waypoint `distance_m` away: three times the ideal
/// turn-then-drive time plus 10 s. Longer means the robot is stuck.
double TimeBudgetS(double distance_m, const ControllerConfig& c) {
  return 3.0 * (distance_m / c.max_speed_mps + M_PI / c.max_turn_rate_rps + 2.0 * c.max_speed_mps / c.accel_mps2) + 10.0;
}
}  // namespace

Stream Simulate(const Scenario& scenario, std::uint64_t seed, const SimulationOptions& options,
                SimulationReport* report) {
  const double dt = options.dt_s;
  Stream stream;
  StreamHeader& h = stream.header;
  h.slambox_version = kVersion;
  h.scenario_name = scenario.name;
  h.scenario_yaml = ScenarioToYaml(scenario);
  h.seed = seed;
  h.dt_s = dt;
  h.sensors = scenario.sensors;
  h.world = MakeWorld(scenario);

  PhysicsWorld physics(scenario, h.world);
  const StaticGeometryIndex statics(StaticGeometryOf(h.world));
  RayScene scene{&statics, {}};
  ControllerConfig control;
  control.max_speed_mps = scenario.robot.max_speed_mps;
  control.max_turn_rate_rps = scenario.robot.max_turn_rate_deg_s * M_PI / 180.0;
  WaypointController controller(scenario.robot.path, scenario.robot.laps, control);

  SE2 pose = physics.RobotPose();
  h.start_pose = pose;
  const SensorSuite& cfg = scenario.sensors;
  std::optional<OdometrySensor> odometry;
  std::optional<GyroSensor> gyro;
  std::optional<LidarSensor> lidar;
  std::optional<LandmarkSensor> landmarks;
  if (cfg.odometry) odometry.emplace(*cfg.odometry, seed, pose);
  if (cfg.gyro && cfg.gyro->rate_hz > 0.0) gyro.emplace(*cfg.gyro, seed);
  if (cfg.lidar) lidar.emplace(*cfg.lidar, seed);
  if (cfg.landmarks) landmarks.emplace(*cfg.landmarks, seed);
  const long odo_every = odometry ? StepsPerEvent(cfg.odometry->rate_hz, dt) : 0;
  const long gyro_every = gyro ? StepsPerEvent(cfg.gyro->rate_hz, dt) : 0;
  const long lidar_every = lidar ? StepsPerEvent(cfg.lidar->rate_hz, dt) : 0;
  const long lm_every = landmarks ? StepsPerEvent(cfg.landmarks->rate_hz, dt) : 0;

  auto fire_sensors = [&](long k) {
    const double t = static_cast<double>(k) * dt;
    if (odometry && k > 0 && k % odo_every == 0) stream.events.push_back(odometry->Measure(t, pose));
    if (gyro && k % gyro_every == 0) stream.events.push_back(gyro->Measure(t, physics.RobotYawRate()));
    const bool scan = lidar && k % lidar_every == 0, detect = landmarks && k % lm_every == 0;
    if ((scan || detect) && !scenario.movers.empty()) scene.movers = physics.Movers();
    if (scan) stream.events.push_back(lidar->Scan(t, pose, scene));
    if (detect) stream.events.push_back(landmarks->Detect(t, pose, h.world.landmarks, scene));
  };

  const long fixed_steps = scenario.duration_s > 0.0 ? std::lround(scenario.duration_s / dt) : -1;
  const long max_steps = std::lround(options.max_duration_s / dt);
  const long kidnap_step =
      scenario.robot.kidnap ? std::max(1L, static_cast<long>(std::ceil(scenario.robot.kidnap->at_s / dt - 1e-9))) : -1;
  stream.groundtruth.push_back({0.0, pose});
  fire_sensors(0);

  SimulationReport rep;
  int current_target = -1;
  long target_since_step = 0;
  double target_budget_s = 0.0;
  long k = 1;
  for (;; ++k) {
    if (fixed_steps >= 0 && k > fixed_steps) break;
    const VelocityCommand cmd = controller.Update(pose, dt);
    if (fixed_steps < 0 && controller.done()) break;
    if (!controller.done() && controller.target() != current_target) {
      current_target = controller.target();
      target_since_step = k;
      target_budget_s = TimeBudgetS((controller.target_position() - pose.translation()).norm(), control);
    }
    if (!controller.done() && static_cast<double>(k - target_since_step) * dt > target_budget_s) {
      const int n = static_cast<int>(scenario.robot.path.size());
      throw InputError(scenario.source, 0,
                       "the robot cannot reach robot.path waypoint " + std::to_string(current_target % n) + " " +
                           Xy(controller.target_position()) + " (lap " + std::to_string(current_target / n + 1) +
                           ") within " + std::to_string(static_cast<int>(target_budget_s)) + " s: stuck at " +
                           Xy(pose.translation()) + " after " + std::to_string(physics.contacts().robot_wall) +
                           " wall contacts",
                       "move that waypoint (or the walls) so the straight line from the previous waypoint is "
                       "free by more than robot.radius_m");
    }
    if (fixed_steps < 0 && k > max_steps)
      throw InputError(scenario.source, 0, "the robot did not finish its path within " +
                                               std::to_string(options.max_duration_s) + " s",
                       "shorten robot.path or robot.laps, or set duration_s");
    physics.SetRobotVelocity(cmd.v_mps, cmd.w_rps);
    physics.Step(dt, static_cast<double>(k) * dt);
    SE2 now = physics.RobotPose();
    rep.distance_m += (now.translation() - pose.translation()).norm();
    if (k == kidnap_step) {  // teleport; odometry keeps measuring the wheels only
      const SE2 to = ToPose(scenario.robot.kidnap->to);
      physics.TeleportRobot(to);
      const SE2 landed = physics.RobotPose();
      if (odometry) odometry->Teleport(now, landed);
      now = landed;
      target_since_step = k;
      target_budget_s = controller.done() ? 0.0 : TimeBudgetS((controller.target_position() - now.translation()).norm(), control);
    }
    pose = now;
    stream.groundtruth.push_back({static_cast<double>(k) * dt, pose});
    fire_sensors(k);
  }
  h.duration_s = static_cast<double>(k - 1) * dt;
  rep.steps = k - 1;
  rep.path_completed = controller.done();
  rep.wall_contacts = physics.contacts().robot_wall;
  rep.mover_contacts = physics.contacts().robot_mover;
  if (report) *report = rep;
  return stream;
}

}  // namespace slambox
