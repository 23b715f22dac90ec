// YAML tree -> Scenario: every key checked against the schema, every value typed and
// range-checked (DESIGN.md, "Scenario file (YAML, version 1)").
#include <filesystem>
#include <set>

#include "core/error.hpp"
#include "core/limits.hpp"
#include "core/ros_map.hpp"

#include "sim/scenario_yaml.hpp"

namespace slambox::scenario_detail {
namespace {

std::string Item(const std::string& list, std::size_t i) { return list + "[" + std::to_string(i) + "]"; }

YAML::Node Required(const YamlSource& src, const YAML::Node& map, const std::string& path, const std::string& key,
                    const std::string& example) {
  const YAML::Node v = map[key];
  if (!v.IsDefined() || v.IsNull())
    Fail(src, map, "missing required key '" + (path.empty() ? key : path + "." + key) + "'",
         "add it, e.g. " + example);
  return v;
}

YAML::Node Sequence(const YamlSource& src, const YAML::Node& map, const std::string& key) {
  const YAML::Node v = map[key];
  if (!v.IsDefined() || v.IsNull()) return YAML::Node(YAML::NodeType::Sequence);
  if (!v.IsSequence()) Fail(src, v, key + " must be a list", "write each item on a line starting with '- '");
  CheckListSize(src, v, key);
  return v;
}

// The map.yaml path is relative to the scenario file (absolute paths as given). A built-in
// scenario's relative path, or any path written `builtin:maps/NAME.yaml` (as `scenario show`
// prints it), names a file of scenarios/maps/ embedded in the binary.
constexpr const char* kBuiltinPrefix = "builtin:";

std::string EmbeddedFileBytes(const std::string& path) {
  const std::string name = path.substr(std::string(kBuiltinPrefix).size());
  for (const auto& f : EmbeddedFiles())
    if (name == f.path) return std::string(reinterpret_cast<const char*>(f.data), f.size);
  std::string known;
  for (const auto& f : EmbeddedFiles()) known += (known.empty() ? "" : ", ") + std::string(f.path);
  throw InputError(path, 0, "no such built-in map file (built in: " + (known.empty() ? "none" : known) + ")",
                   "name one of them, or give a path to a map.yaml on disk");
}

void ParseOccupancyMap(const YamlSource& src, const YAML::Node& node, Scenario& s) {
  const std::string value = ReadString(src, node, "world.occupancy_map");
  const bool builtin_source = src.file.rfind(kBuiltinPrefix, 0) == 0;
  const bool embedded = value.rfind(kBuiltinPrefix, 0) == 0 || (builtin_source && std::filesystem::path(value).is_relative());
  if (embedded) {
    const std::string name = value.rfind(kBuiltinPrefix, 0) == 0 ? value.substr(std::string(kBuiltinPrefix).size()) : value;
    s.occupancy_map = kBuiltinPrefix + std::filesystem::path(name).lexically_normal().string();
  } else {
    std::filesystem::path path(value);
    if (path.is_relative()) path = std::filesystem::path(src.file).parent_path() / path;
    s.occupancy_map = std::filesystem::absolute(path).lexically_normal().string();
  }
  s.occupancy_map_line = LineOf(src, node);
  try {
    s.occupancy_grid = embedded ? ReadRosMap(s.occupancy_map, EmbeddedFileBytes) : ReadRosMap(s.occupancy_map);
  } catch (const InputError& e) {
    Fail(src, node, std::string("world.occupancy_map: ") + e.what(), "give a ROS map.yaml (image, resolution, origin, ...)");
  }
  if (s.occupancy_grid.resolution_m < 0.01)
    Fail(src, node, "world.occupancy_map: resolution below 0.01 m", "resample the map to cells of at least 1 cm");
}

PoseSpec ParsePose(const YamlSource& src, const YAML::Node& node, const std::string& path) {
  CheckMap(src, node, path);
  PoseSpec p;
  const Range coordinate = Between(-limits::kMaxCoordinateM, limits::kMaxCoordinateM);
  p.x = GetDouble(src, node, path, "x", p.x, coordinate);
  p.y = GetDouble(src, node, path, "y", p.y, coordinate);
  p.theta_deg = GetDouble(src, node, path, "theta_deg", p.theta_deg, {});
  return p;
}

WallSpec ParseWall(const YamlSource& src, const YAML::Node& node, std::size_t i) {
  const std::string label = Item("world.walls", i);
  CheckMap(src, node, "world.walls.#");
  if (node.size() != 1)
    Fail(src, node, label + " must have exactly one of polyline, polygon, box, circle",
         "write one wall per list item, e.g. - box: {center: [5, 5], size: [1, 2]}");
  WallSpec w;
  w.line = LineOf(src, node);
  const std::string kind = node.begin()->first.Scalar();
  const YAML::Node v = node.begin()->second;
  if (kind == "polyline") {
    w.kind = WallSpec::Kind::kPolyline;
    w.points = ReadPoints(src, v, label + ".polyline", 2);
  } else if (kind == "polygon") {
    w.kind = WallSpec::Kind::kPolygon;
    w.points = ReadPoints(src, v, label + ".polygon", 3);
  } else if (kind == "box") {
    w.kind = WallSpec::Kind::kBox;
    CheckMap(src, v, "world.walls.#.box");
    w.center = ReadPoint(src, Required(src, v, label + ".box", "center", "center: [5, 5]"), label + ".box.center");
    w.size = ReadPoint(src, Required(src, v, label + ".box", "size", "size: [1, 2]"), label + ".box.size");
    if (w.size.minCoeff() <= 0.0)
      Fail(src, v["size"], label + ".box.size must be positive in both directions", "write size: [width_m, height_m] > 0");
    w.angle_deg = GetDouble(src, v, label + ".box", "angle_deg", 0.0, {});
  } else {
    w.kind = WallSpec::Kind::kCircle;
    CheckMap(src, v, "world.walls.#.circle");
    w.center = ReadPoint(src, Required(src, v, label + ".circle", "center", "center: [3, 4]"), label + ".circle.center");
    w.radius_m = ReadDouble(src, Required(src, v, label + ".circle", "radius_m", "radius_m: 0.3"),
                            label + ".circle.radius_m", Above(0.0));
  }
  return w;
}

std::vector<LandmarkSpec> ParseLandmarks(const YamlSource& src, const YAML::Node& list) {
  std::vector<LandmarkSpec> out;
  std::set<int> ids;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node n = list[i];
    const std::string label = Item("world.landmarks", i);
    CheckMap(src, n, "world.landmarks.#");
    LandmarkSpec l;
    l.line = LineOf(src, n);
    l.pos = ReadPoint(src, Required(src, n, label, "pos", "pos: [4, 2]"), label + ".pos");
    l.radius_m = GetDouble(src, n, label, "radius_m", l.radius_m, Above(0.0));
    l.id = GetInt(src, n, label, "id", static_cast<int>(i), AtLeast(0));
    if (!ids.insert(l.id).second)
      Fail(src, n["id"].IsDefined() ? n["id"] : n, "duplicate landmark id " + std::to_string(l.id) + " in " + label,
           "give every landmark a distinct id (a landmark without `id:` takes its list index)");
    out.push_back(l);
  }
  return out;
}

MoverSpec ParseMover(const YamlSource& src, const YAML::Node& n, std::size_t i) {
  const std::string label = Item("world.movers", i);
  CheckMap(src, n, "world.movers.#");
  MoverSpec m;
  m.line = LineOf(src, n);
  const YAML::Node circle = n["circle"], box = n["box"];
  if (circle.IsDefined() == box.IsDefined())
    Fail(src, n, label + " must have exactly one shape, circle or box",
         "write circle: {radius_m: 0.3} or box: {size: [0.8, 0.5]}");
  if (circle.IsDefined()) {
    CheckMap(src, circle, "world.movers.#.circle");
    m.radius_m = GetDouble(src, circle, label + ".circle", "radius_m", m.radius_m, Above(0.0));
  } else {
    m.is_box = true;
    CheckMap(src, box, "world.movers.#.box");
    if (box["size"].IsDefined()) m.size = ReadPoint(src, box["size"], label + ".box.size");
    if (m.size.minCoeff() <= 0.0)
      Fail(src, box["size"], label + ".box.size must be positive in both directions", "write size: [0.8, 0.5]");
  }
  m.path = ReadPoints(src, Required(src, n, label, "path", "path: [[1, 1], [8, 1]]"), label + ".path", 2);
  m.speed_mps = GetDouble(src, n, label, "speed_mps", m.speed_mps, Above(0.0));
  m.loop = GetBool(src, n, label, "loop", m.loop);
  return m;
}

RobotSpec ParseRobot(const YamlSource& src, const YAML::Node& n) {
  CheckMap(src, n, "robot");
  RobotSpec r;
  if (n["start"].IsDefined()) {
    r.start = ParsePose(src, n["start"], "robot.start");
    r.start_line = LineOf(src, n["start"]);
  } else {
    r.start_line = LineOf(src, n);
  }
  r.radius_m = GetDouble(src, n, "robot", "radius_m", r.radius_m, Above(0.0));
  r.max_speed_mps = GetDouble(src, n, "robot", "max_speed_mps", r.max_speed_mps, Above(0.0));
  r.max_turn_rate_deg_s = GetDouble(src, n, "robot", "max_turn_rate_deg_s", r.max_turn_rate_deg_s, Above(0.0));
  const YAML::Node path = Required(src, n, "robot", "path", "path: [[1, 1], [18, 1]]");
  r.path = ReadPoints(src, path, "robot.path", 1);
  for (std::size_t i = 0; i < path.size(); ++i) r.path_lines.push_back(LineOf(src, path[i]));
  r.laps = GetInt(src, n, "robot", "laps", r.laps, AtLeast(1));
  if (n["kidnap"].IsDefined()) {
    const YAML::Node k = n["kidnap"];
    CheckMap(src, k, "robot.kidnap");
    KidnapSpec kidnap;
    kidnap.line = LineOf(src, k);
    kidnap.at_s = ReadDouble(src, Required(src, k, "robot.kidnap", "at_s", "at_s: 60"), "robot.kidnap.at_s", AtLeast(0));
    kidnap.to = ParsePose(src, Required(src, k, "robot.kidnap", "to", "to: {x: 5, y: 5, theta_deg: 90}"),
                          "robot.kidnap.to");
    r.kidnap = kidnap;
  }
  return r;
}

}  // namespace

Scenario ParseScenario(const YAML::Node& root, const YamlSource& src) {
  if (!root.IsDefined() || root.IsNull())
    Fail(src, root, "the scenario is empty", "start the file with `version: 1` (see `slambox scenario show loop`)");
  if (!root.IsMap())
    Fail(src, root, "a scenario must be a YAML mapping, got " + std::string(root.IsSequence() ? "a list" : "plain text"),
         "write `key: value` lines starting with `version: 1` (see `slambox scenario show loop`)");
  CheckMap(src, root, "");
  Scenario s;
  const YAML::Node version = Required(src, root, "", "version", "version: 1");
  s.version = ReadInt(src, version, "version", {});
  if (s.version != 1)
    Fail(src, version, "unsupported scenario version " + std::to_string(s.version), "this slambox reads version: 1");
  if (root["name"].IsDefined()) s.name = ReadString(src, root["name"], "name");
  if (root["description"].IsDefined()) s.description = ReadString(src, root["description"], "description");
  s.duration_s = GetDouble(src, root, "", "duration_s", s.duration_s, Between(0.0, limits::kMaxDurationS));

  if (root["world"].IsDefined() && !root["world"].IsNull()) {
    const YAML::Node world = root["world"];
    CheckMap(src, world, "world");
    if (world["occupancy_map"].IsDefined()) ParseOccupancyMap(src, world["occupancy_map"], s);
    const YAML::Node walls = Sequence(src, world, "walls");
    for (std::size_t i = 0; i < walls.size(); ++i) s.walls.push_back(ParseWall(src, walls[i], i));
    s.landmarks = ParseLandmarks(src, Sequence(src, world, "landmarks"));
    const YAML::Node movers = Sequence(src, world, "movers");
    for (std::size_t i = 0; i < movers.size(); ++i) s.movers.push_back(ParseMover(src, movers[i], i));
  }
  s.robot = ParseRobot(src, Required(src, root, "", "robot", "robot: {path: [[1, 1], [5, 1]]}"));
  if (root["sensors"].IsDefined() && !root["sensors"].IsNull()) s.sensors = ParseSensors(root["sensors"], src);
  s.source = src.file;
  return s;
}

}  // namespace slambox::scenario_detail
