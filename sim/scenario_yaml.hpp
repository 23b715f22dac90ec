#pragma once
// Internal to sim/: reading a scenario's YAML tree with errors that name the file, the
// line and the fix. Nodes that came from `--set` are reported as that override.
#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <string>

#include "core/range.hpp"
#include <vector>

#include "sim/scenario.hpp"

// Internal names live in their own namespace so they never collide with other layers.
namespace slambox::scenario_detail {

/// Where the tree came from: the file (or "builtin:NAME") and the `--set` values that
/// were grafted into it (each value node with "FILE (--set key=value)", used as the
/// file name in errors about it).
struct YamlSource {
  std::string file;
  std::vector<std::pair<YAML::Node, std::string>> overrides;
  /// Points read so far (YAML aliases can repeat one list many times: the total is bounded).
  mutable std::size_t points_read = 0;
};

/// Keys allowed in the mapping at `path` ("" = top level, "sensors.lidar",
/// "world.walls.#.box" where # is any list item); nullptr where the schema has no mapping.
const std::vector<std::string>* ScenarioKeysAt(const std::string& path);
std::string JoinKeys(const std::vector<std::string>& keys);

/// 1-based line of `node` in the file; 0 when unknown or when it came from `--set`.
int LineOf(const YamlSource& src, const YAML::Node& node);
[[noreturn]] void Fail(const YamlSource& src, const YAML::Node& at, const std::string& problem,
                       const std::string& fix);

/// `node` must be a mapping whose keys are all in the schema at `path`.
void CheckMap(const YamlSource& src, const YAML::Node& node, const std::string& path);


double ReadDouble(const YamlSource& src, const YAML::Node& value, const std::string& key, Range range);
int ReadInt(const YamlSource& src, const YAML::Node& value, const std::string& key, Range range);
bool ReadBool(const YamlSource& src, const YAML::Node& value, const std::string& key);
std::string ReadString(const YamlSource& src, const YAML::Node& value, const std::string& key);
Eigen::Vector2d ReadPoint(const YamlSource& src, const YAML::Node& value, const std::string& key);
/// `list` has at most limits::kMaxListItems items.
void CheckListSize(const YamlSource& src, const YAML::Node& list, const std::string& key);
std::vector<Eigen::Vector2d> ReadPoints(const YamlSource& src, const YAML::Node& value,
                                        const std::string& key, std::size_t min_count);

/// Optional field `map[key]` at schema `path`: `fallback` when absent.
double GetDouble(const YamlSource& src, const YAML::Node& map, const std::string& path,
                 const std::string& key, double fallback, Range range);
int GetInt(const YamlSource& src, const YAML::Node& map, const std::string& path, const std::string& key,
           int fallback, Range range);
bool GetBool(const YamlSource& src, const YAML::Node& map, const std::string& path, const std::string& key,
             bool fallback);

/// The tree -> Scenario, every field validated (types, ranges, required keys).
Scenario ParseScenario(const YAML::Node& root, const YamlSource& src);
SensorSuite ParseSensors(const YAML::Node& node, const YamlSource& src);

/// Applies "dotted.key=value" overrides to the tree (before validation); records each
/// grafted node in `src`. Throws InputError for an unknown key or an unparsable value.
void ApplyOverrides(YAML::Node& root, const std::vector<std::string>& overrides, YamlSource& src);

/// Geometry: robot start clear of walls and posts, every waypoint segment clear, movers'
/// paths clear of static walls. Throws InputError naming the offending line.
void CheckScenarioGeometry(const Scenario& scenario);
/// The limits of core/limits.hpp that need the whole scenario: the stream's estimated
/// memory and the geometry check's work (sim/scenario_limits.hpp). Throws InputError.
void CheckScenarioSize(const Scenario& scenario);

/// Built-in scenario texts embedded at build time: {name, yaml}.
struct EmbeddedScenario {
  const char* name;
  const char* yaml;
};
const std::vector<EmbeddedScenario>& EmbeddedScenarios();

/// The files of scenarios/maps/ embedded beside them (map.yaml + image), so a built-in
/// scenario can name `occupancy_map: maps/NAME.yaml`: {path relative to scenarios/, bytes}.
struct EmbeddedFile {
  const char* path;
  const unsigned char* data;
  std::size_t size;
};
const std::vector<EmbeddedFile>& EmbeddedFiles();

}  // namespace slambox::scenario_detail
