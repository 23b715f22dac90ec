// `sensors:` block -> SensorSuite. A missing block = the sensor is absent; a present
// block takes the defaults of core/sensors.hpp for every key it does not give.
#include "core/limits.hpp"
#include "sim/scenario_yaml.hpp"

namespace slambox::scenario_detail {
namespace {

const Range kProbability = Between(0.0, 1.0);
const Range kFov = Range{.min = 0.0, .max = 360.0, .min_open = true};

OdometryConfig ParseOdometry(const YamlSource& src, const YAML::Node& n) {
  const std::string p = "sensors.odometry";
  CheckMap(src, n, p);
  OdometryConfig c;
  c.rate_hz = GetDouble(src, n, p, "rate_hz", c.rate_hz, Above(0.0));
  if (const YAML::Node a = n["alpha"]; a.IsDefined()) {
    if (!a.IsSequence() || a.size() != 4)
      Fail(src, a, p + ".alpha must be a list of 4 numbers a1..a4 (Thrun's odometry model)",
           "write alpha: [0.05, 0.005, 0.05, 0.005]");
    for (std::size_t i = 0; i < 4; ++i)
      c.alpha[i] = ReadDouble(src, a[i], p + ".alpha[" + std::to_string(i) + "]", AtLeast(0.0));
  }
  return c;
}

LidarConfig ParseLidar(const YamlSource& src, const YAML::Node& n) {
  const std::string p = "sensors.lidar";
  CheckMap(src, n, p);
  LidarConfig c;
  c.rate_hz = GetDouble(src, n, p, "rate_hz", c.rate_hz, Above(0.0));
  c.beams = GetInt(src, n, p, "beams", c.beams, Between(1, limits::kMaxLidarBeams));
  c.fov_deg = GetDouble(src, n, p, "fov_deg", c.fov_deg, kFov);
  c.range_min_m = GetDouble(src, n, p, "range_min_m", c.range_min_m, AtLeast(0.0));
  c.range_max_m = GetDouble(src, n, p, "range_max_m", c.range_max_m, Above(c.range_min_m));
  c.sigma_range_m = GetDouble(src, n, p, "sigma_range_m", c.sigma_range_m, AtLeast(0.0));
  c.sigma_bearing_deg = GetDouble(src, n, p, "sigma_bearing_deg", c.sigma_bearing_deg, AtLeast(0.0));
  c.dropout_prob = GetDouble(src, n, p, "dropout_prob", c.dropout_prob, kProbability);
  return c;
}

LandmarkSensorConfig ParseLandmarkSensor(const YamlSource& src, const YAML::Node& n) {
  const std::string p = "sensors.landmarks";
  CheckMap(src, n, p);
  LandmarkSensorConfig c;
  c.rate_hz = GetDouble(src, n, p, "rate_hz", c.rate_hz, Above(0.0));
  c.range_max_m = GetDouble(src, n, p, "range_max_m", c.range_max_m, Above(0.0));
  c.fov_deg = GetDouble(src, n, p, "fov_deg", c.fov_deg, kFov);
  c.sigma_range_m = GetDouble(src, n, p, "sigma_range_m", c.sigma_range_m, AtLeast(0.0));
  c.sigma_bearing_deg = GetDouble(src, n, p, "sigma_bearing_deg", c.sigma_bearing_deg, AtLeast(0.0));
  c.known_ids = GetBool(src, n, p, "known_ids", c.known_ids);
  c.detection_prob = GetDouble(src, n, p, "detection_prob", c.detection_prob, kProbability);
  c.detection_prob_known = GetBool(src, n, p, "detection_prob_known", c.detection_prob_known);
  c.clutter_per_scan = GetDouble(src, n, p, "clutter_per_scan", c.clutter_per_scan, Between(0.0, limits::kMaxClutterPerScan));
  return c;
}

GyroConfig ParseGyro(const YamlSource& src, const YAML::Node& n) {
  const std::string p = "sensors.gyro";
  CheckMap(src, n, p);
  GyroConfig c;
  c.rate_hz = GetDouble(src, n, p, "rate_hz", c.rate_hz, AtLeast(0.0));
  c.sigma_dps = GetDouble(src, n, p, "sigma_dps", c.sigma_dps, AtLeast(0.0));
  c.bias_dps = GetDouble(src, n, p, "bias_dps", c.bias_dps, {});
  return c;
}

}  // namespace

SensorSuite ParseSensors(const YAML::Node& node, const YamlSource& src) {
  CheckMap(src, node, "sensors");
  SensorSuite s;
  // A block written as `lidar: {}` is present with every default; `lidar: null` or no
  // block at all means the sensor is absent.
  auto present = [&](const char* key) { return node[key].IsDefined() && !node[key].IsNull(); };
  if (present("odometry")) s.odometry = ParseOdometry(src, node["odometry"]);
  if (present("lidar")) s.lidar = ParseLidar(src, node["lidar"]);
  if (present("landmarks")) s.landmarks = ParseLandmarkSensor(src, node["landmarks"]);
  if (present("gyro")) s.gyro = ParseGyro(src, node["gyro"]);
  return s;
}

}  // namespace slambox::scenario_detail
