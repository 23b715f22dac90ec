// The schema's key table and typed reads of YAML nodes with file:line errors.
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "core/error.hpp"
#include "sim/scenario_yaml.hpp"

#include "core/limits.hpp"

namespace slambox::scenario_detail {

const std::vector<std::string>* ScenarioKeysAt(const std::string& path) {
  static const std::map<std::string, std::vector<std::string>> kKeys = {
      {"", {"version", "name", "description", "duration_s", "world", "robot", "sensors"}},
      {"world", {"occupancy_map", "walls", "landmarks", "movers"}},
      {"world.walls.#", {"polyline", "polygon", "box", "circle"}},
      {"world.walls.#.box", {"center", "size", "angle_deg"}},
      {"world.walls.#.circle", {"center", "radius_m"}},
      {"world.landmarks.#", {"pos", "radius_m", "id"}},
      {"world.movers.#", {"circle", "box", "path", "speed_mps", "loop"}},
      {"world.movers.#.circle", {"radius_m"}},
      {"world.movers.#.box", {"size"}},
      {"robot", {"start", "radius_m", "max_speed_mps", "max_turn_rate_deg_s", "path", "laps", "kidnap"}},
      {"robot.start", {"x", "y", "theta_deg"}},
      {"robot.kidnap", {"at_s", "to"}},
      {"robot.kidnap.to", {"x", "y", "theta_deg"}},
      {"sensors", {"odometry", "lidar", "landmarks", "gyro"}},
      {"sensors.odometry", {"rate_hz", "alpha"}},
      {"sensors.lidar",
       {"rate_hz", "beams", "fov_deg", "range_min_m", "range_max_m", "sigma_range_m", "sigma_bearing_deg",
        "dropout_prob"}},
      {"sensors.landmarks",
       {"rate_hz", "range_max_m", "fov_deg", "sigma_range_m", "sigma_bearing_deg", "known_ids",
        "detection_prob", "detection_prob_known", "clutter_per_scan"}},
      {"sensors.gyro", {"rate_hz", "sigma_dps", "bias_dps"}},
  };
  auto it = kKeys.find(path);
  return it == kKeys.end() ? nullptr : &it->second;
}

std::string JoinKeys(const std::vector<std::string>& keys) {
  std::string out;
  for (const auto& k : keys) out += (out.empty() ? "" : ", ") + k;
  return out;
}

namespace {
bool Contains(const YAML::Node& tree, const YAML::Node& node) {
  if (tree.is(node)) return true;
  if (tree.IsSequence() || tree.IsMap())
    for (const auto& it : tree)
      if (Contains(tree.IsMap() ? it.second : it, node) || (tree.IsMap() && it.first.is(node))) return true;
  return false;
}

const std::string* OverrideOf(const YamlSource& src, const YAML::Node& node) {
  for (const auto& [value, text] : src.overrides)
    if (Contains(value, node)) return &text;
  return nullptr;
}

void CheckRange(const YamlSource& src, const YAML::Node& value, const std::string& key, double v,
                const Range& r) {
  if (!InRange(r, v))
    Fail(src, value, key + " = " + value.Scalar() + " is out of range", "set " + key + " to a value " + Describe(r));
}

void ExpectScalar(const YamlSource& src, const YAML::Node& value, const std::string& key, const char* what) {
  if (!value.IsScalar() || value.IsNull())
    Fail(src, value, key + " must be " + what + (value.IsNull() ? ", but it has no value" : ", not a list or mapping"),
         std::string("write ") + key + ": <" + what + ">");
}
}  // namespace

void CheckListSize(const YamlSource& src, const YAML::Node& list, const std::string& key) {
  if (list.size() > limits::kMaxListItems)
    Fail(src, list, key + " has " + std::to_string(list.size()) + " items, over the limit of " +
                        std::to_string(limits::kMaxListItems),
         "split the world or simplify it (fewer points, walls, posts or waypoints)");
}

int LineOf(const YamlSource& src, const YAML::Node& node) {
  if (!node.IsDefined() || OverrideOf(src, node)) return 0;
  const YAML::Mark mark = node.Mark();
  return mark.is_null() ? 0 : mark.line + 1;
}

void Fail(const YamlSource& src, const YAML::Node& at, const std::string& problem, const std::string& fix) {
  if (at.IsDefined())
    if (const std::string* text = OverrideOf(src, at))
      throw InputError(*text, 0, problem, fix);
  throw InputError(src.file, LineOf(src, at), problem, fix);
}

void CheckMap(const YamlSource& src, const YAML::Node& node, const std::string& path) {
  const std::string label = path.empty() ? "the top level" : path;
  const std::vector<std::string>* keys = ScenarioKeysAt(path);
  if (!node.IsMap())
    Fail(src, node, label + " must be a mapping of keys", "write `key: value` lines; valid keys: " + JoinKeys(*keys));
  std::vector<std::string> seen;
  for (const auto& it : node) {
    const std::string key = it.first.Scalar();
    if (std::find(seen.begin(), seen.end(), key) != seen.end())
      Fail(src, it.first, "duplicate key '" + key + "' in " + label, "keep one of them (YAML uses only the first)");
    seen.push_back(key);
    bool known = false;
    for (const auto& k : *keys) known = known || k == key;
    if (!known)
      Fail(src, it.first, "unknown key '" + key + "' in " + label,
           "remove it or use one of: " + JoinKeys(*keys));
  }
}


double ReadDouble(const YamlSource& src, const YAML::Node& value, const std::string& key, Range range) {
  ExpectScalar(src, value, key, "a number");
  double v = 0.0;
  try {
    v = value.as<double>();
  } catch (const YAML::Exception&) {
    Fail(src, value, key + " must be a number, got '" + value.Scalar() + "'", "write a number, e.g. " + key + ": 1.5");
  }
  if (!std::isfinite(v)) Fail(src, value, key + " must be finite, got '" + value.Scalar() + "'", "write a finite number");
  CheckRange(src, value, key, v, range);
  return v;
}

int ReadInt(const YamlSource& src, const YAML::Node& value, const std::string& key, Range range) {
  ExpectScalar(src, value, key, "an integer");
  int v = 0;
  try {
    v = value.as<int>();
  } catch (const YAML::Exception&) {
    Fail(src, value, key + " must be an integer, got '" + value.Scalar() + "'", "write a whole number, e.g. " + key + ": 2");
  }
  CheckRange(src, value, key, v, range);
  return v;
}

bool ReadBool(const YamlSource& src, const YAML::Node& value, const std::string& key) {
  ExpectScalar(src, value, key, "true or false");
  try {
    return value.as<bool>();
  } catch (const YAML::Exception&) {
    Fail(src, value, key + " must be true or false, got '" + value.Scalar() + "'", "write " + key + ": true");
  }
}

std::string ReadString(const YamlSource& src, const YAML::Node& value, const std::string& key) {
  ExpectScalar(src, value, key, "text");
  return value.Scalar();
}

Eigen::Vector2d ReadPoint(const YamlSource& src, const YAML::Node& value, const std::string& key) {
  if (!value.IsSequence() || value.size() != 2)
    Fail(src, value, key + " must be a point [x, y] in metres", "write it as [x, y], e.g. [1.5, 2]");
  if (++src.points_read > limits::kMaxScenarioPoints)
    Fail(src, value, "more than " + std::to_string(limits::kMaxScenarioPoints) + " points in the scenario (at " + key + ")",
         "draw the world with fewer points (YAML aliases count each time they are used)");
  const Range coordinate = Between(-limits::kMaxCoordinateM, limits::kMaxCoordinateM);
  return {ReadDouble(src, value[0], key + "[0]", coordinate), ReadDouble(src, value[1], key + "[1]", coordinate)};
}

std::vector<Eigen::Vector2d> ReadPoints(const YamlSource& src, const YAML::Node& value, const std::string& key,
                                        std::size_t min_count) {
  if (!value.IsSequence() || value.size() < min_count)
    Fail(src, value,
         key + " must be a list of " + (min_count == 1 ? std::string("one or more points")
                                                       : "at least " + std::to_string(min_count) + " points"),
         "write it as [[x, y], [x, y], ...]");
  CheckListSize(src, value, key);
  std::vector<Eigen::Vector2d> points;
  for (std::size_t i = 0; i < value.size(); ++i)
    points.push_back(ReadPoint(src, value[i], key + "[" + std::to_string(i) + "]"));
  return points;
}

namespace {
std::string Dotted(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }
}  // namespace

double GetDouble(const YamlSource& src, const YAML::Node& map, const std::string& path, const std::string& key,
                 double fallback, Range range) {
  const YAML::Node v = map[key];
  return v.IsDefined() ? ReadDouble(src, v, Dotted(path, key), range) : fallback;
}

int GetInt(const YamlSource& src, const YAML::Node& map, const std::string& path, const std::string& key, int fallback,
           Range range) {
  const YAML::Node v = map[key];
  return v.IsDefined() ? ReadInt(src, v, Dotted(path, key), range) : fallback;
}

bool GetBool(const YamlSource& src, const YAML::Node& map, const std::string& path, const std::string& key,
             bool fallback) {
  const YAML::Node v = map[key];
  return v.IsDefined() ? ReadBool(src, v, Dotted(path, key)) : fallback;
}

}  // namespace slambox::scenario_detail
