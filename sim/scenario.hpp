#pragma once
// A scenario file (DESIGN.md, "Scenario file (YAML, version 1)") as plain data.
// Lengths in metres; angles in degrees, as in the file (converted where used).
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "core/estimate.hpp"
#include "core/sensors.hpp"
#include "core/world.hpp"

namespace slambox {

struct WallSpec {
  enum class Kind { kPolyline, kPolygon, kBox, kCircle };
  Kind kind = Kind::kPolyline;
  std::vector<Eigen::Vector2d> points;  ///< polyline / polygon vertices [m]
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  ///< box / circle [m]
  Eigen::Vector2d size = Eigen::Vector2d::Zero();    ///< box full extents [m]
  double angle_deg = 0.0;                            ///< box rotation
  double radius_m = 0.0;                             ///< circle
  int line = 0;                                      ///< line in the source file, for errors
};

struct LandmarkSpec {
  Eigen::Vector2d pos = Eigen::Vector2d::Zero();
  double radius_m = 0.1;
  int id = 0;  ///< index in the list unless `id:` is given
  int line = 0;
};

struct MoverSpec {
  bool is_box = false;
  double radius_m = 0.3;                             ///< circle movers
  Eigen::Vector2d size = Eigen::Vector2d(0.8, 0.5);  ///< box movers [m]
  std::vector<Eigen::Vector2d> path;
  double speed_mps = 1.0;
  bool loop = true;  ///< true: back and forth forever; false: stop at the end
  int line = 0;
};

struct PoseSpec {
  double x = 0.0;
  double y = 0.0;
  double theta_deg = 0.0;
};

struct KidnapSpec {
  double at_s = 0.0;
  PoseSpec to;
  int line = 0;  ///< line in the source file, for errors
};

struct RobotSpec {
  PoseSpec start;
  double radius_m = 0.25;
  double max_speed_mps = 1.0;
  double max_turn_rate_deg_s = 90.0;
  std::vector<Eigen::Vector2d> path;  ///< waypoints, followed in order
  int laps = 1;
  std::optional<KidnapSpec> kidnap;
  int start_line = 0;           ///< line of `start:` in the source file, for errors
  std::vector<int> path_lines;  ///< line of each waypoint, for errors
};

struct Scenario {
  int version = 1;
  std::string name;
  std::string description;
  double duration_s = 0.0;  ///< 0 = until the robot finishes its path
  /// `world.occupancy_map`: a ROS map.yaml (path relative to the scenario file), resolved
  /// to an absolute path; its occupied cells' boundaries become walls (sim/grid_contours).
  std::string occupancy_map;
  int occupancy_map_line = 0;
  OccupancyGrid occupancy_grid;  ///< read from occupancy_map (0 x 0 = none)
  std::vector<WallSpec> walls;
  std::vector<LandmarkSpec> landmarks;
  std::vector<MoverSpec> movers;
  RobotSpec robot;
  SensorSuite sensors;
  std::string source;  ///< file path or "builtin:NAME", for error messages
};

struct BuiltinScenario {
  std::string name;
  std::string description;
};

/// The scenarios in scenarios/ (embedded in the binary at build time).
std::vector<BuiltinScenario> BuiltinScenarios();

/// Loads a built-in scenario by name or a YAML file by path, applies `overrides`
/// ("dotted.key=value", value parsed as YAML) and validates everything. Throws
/// InputError naming file, line and the fix.
Scenario LoadScenario(const std::string& name_or_path, const std::vector<std::string>& overrides = {});

/// As LoadScenario, from YAML text (e.g. a stream header's scenario_yaml); `source`
/// names it in errors.
Scenario LoadScenarioText(const std::string& yaml, const std::string& source,
                          const std::vector<std::string>& overrides = {});

/// The scenario as YAML with every default filled in (`slambox scenario show`).
/// LoadScenario of this text gives back an equal Scenario.
std::string ScenarioToYaml(const Scenario& scenario);

/// Ground-truth geometry (walls as segments/circles, posts, mover paths).
World MakeWorld(const Scenario& scenario);

}  // namespace slambox
