// Every schema error is an InputError naming the file, the line and a fix.
#include <gtest/gtest.h>

#include <random>
#include <sstream>

#include "core/error.hpp"
#include "sim/scenario.hpp"
#include "tests/sim/scenario_test_support.hpp"

namespace slambox {
namespace {

// Line numbers in the comments are the 1-based lines the tests refer to.
const std::vector<std::string> kBase = {
    "version: 1",                                                  // 1
    "name: t",                                                     // 2
    "world:",                                                      // 3
    "  walls:",                                                    // 4
    "    - polygon: [[0, 0], [10, 0], [10, 10], [0, 10]]",         // 5
    "    - box: {center: [5, 5], size: [1, 1]}",                   // 6
    "    - circle: {center: [8, 8], radius_m: 0.5}",               // 7
    "  landmarks:",                                                // 8
    "    - {pos: [2, 8]}",                                         // 9
    "    - {pos: [3, 8], id: 5}",                                  // 10
    "robot:",                                                      // 11
    "  start: {x: 1, y: 1, theta_deg: 0}",                         // 12
    "  path: [[9, 1], [9, 4]]",                                    // 13
    "  laps: 1",                                                   // 14
    "sensors:",                                                    // 15
    "  odometry: {rate_hz: 50}",                                   // 16
    "  lidar: {beams: 180}",                                       // 17
    "  landmarks: {range_max_m: 10}",                              // 18
};

/// kBase with line `line` (1-based) replaced by `text` (which may hold several lines).
std::string With(int line, const std::string& text) {
  std::ostringstream out;
  for (int i = 0; i < static_cast<int>(kBase.size()); ++i) out << (i + 1 == line ? text : kBase[i]) << "\n";
  return out.str();
}

struct Case {
  std::string yaml;
  int line;
  std::string problem;  ///< substring of the message
  std::vector<std::string> overrides = {};
};

/// Loads `c.yaml` from a temp file: must fail with file, line, problem and a fix.
void ExpectInputError(const Case& c, const std::string& fix_substring = "") {
  testing::TempDir dir;
  const std::string file = dir.Write("bad.yaml", c.yaml);
  try {
    LoadScenario(file, c.overrides);
    ADD_FAILURE() << "no error for:\n" << c.yaml;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(file), std::string::npos) << msg;
    EXPECT_EQ(e.line(), c.line) << msg;
    if (c.line > 0) {
      EXPECT_NE(msg.find(file + ":" + std::to_string(c.line) + ":"), std::string::npos) << msg;
    }
    EXPECT_NE(msg.find(c.problem), std::string::npos) << "expected '" << c.problem << "' in: " << msg;
    EXPECT_NE(msg.find("\n  fix: "), std::string::npos) << msg;
    EXPECT_NE(msg.find(fix_substring), std::string::npos) << msg;
  }
}

TEST(ScenarioErrors, BaseIsValid) {
  testing::TempDir dir;
  const Scenario s = LoadScenario(dir.Write("ok.yaml", With(0, "")));
  EXPECT_EQ(s.landmarks.at(0).id, 0);
  EXPECT_EQ(s.landmarks.at(1).id, 5);
  EXPECT_EQ(s.walls.at(1).line, 6);
  EXPECT_EQ(s.robot.path_lines, (std::vector<int>{13, 13}));
}

TEST(ScenarioErrors, UnknownKeyAtEveryLevel) {
  ExpectInputError({With(2, "nam: t"), 2, "unknown key 'nam' in the top level"}, "version, name");
  ExpectInputError({With(4, "  wallz:"), 4, "unknown key 'wallz' in world"}, "walls, landmarks, movers");
  ExpectInputError({With(6, "    - bx: {center: [5, 5]}"), 6, "unknown key 'bx' in world.walls.#"}, "polyline");
  ExpectInputError({With(6, "    - box: {center: [5, 5], size: [1, 1], angel_deg: 3}"), 6,
                    "unknown key 'angel_deg' in world.walls.#.box"},
                   "angle_deg");
  ExpectInputError({With(7, "    - circle: {center: [8, 8], r: 0.5}"), 7, "unknown key 'r'"}, "radius_m");
  ExpectInputError({With(9, "    - {pos: [2, 8], radius: 0.1}"), 9, "unknown key 'radius' in world.landmarks.#"},
                   "radius_m");
  ExpectInputError({With(10, "  movers:\n    - {circle: {radius_m: 0.3}, path: [[1, 5], [3, 5]], sped_mps: 1}"), 11,
                    "unknown key 'sped_mps' in world.movers.#"},
                   "speed_mps");
  ExpectInputError({With(10, "  movers:\n    - {circle: {r: 0.3}, path: [[1, 5], [3, 5]]}"), 11,
                    "unknown key 'r' in world.movers.#.circle"});
  ExpectInputError({With(14, "  lapz: 1"), 14, "unknown key 'lapz' in robot"}, "laps");
  ExpectInputError({With(12, "  start: {x: 1, y: 1, theta: 0}"), 12, "unknown key 'theta' in robot.start"},
                   "theta_deg");
  ExpectInputError({With(14, "  kidnap: {at_s: 5, to: {x: 1, y: 1, z: 0}}"), 14, "unknown key 'z' in robot.kidnap.to"});
  ExpectInputError({With(18, "  camera: {}"), 18, "unknown key 'camera' in sensors"}, "odometry, lidar, landmarks, gyro");
  ExpectInputError({With(16, "  odometry: {rate: 50}"), 16, "unknown key 'rate' in sensors.odometry"}, "rate_hz");
  ExpectInputError({With(17, "  lidar: {beams: 180, range_max: 10}"), 17, "unknown key 'range_max' in sensors.lidar"},
                   "range_max_m");
  ExpectInputError({With(18, "  landmarks: {known_id: true}"), 18, "unknown key 'known_id' in sensors.landmarks"});
  ExpectInputError({With(18, "  gyro: {sigma: 0.1}"), 18, "unknown key 'sigma' in sensors.gyro"}, "sigma_dps");
}

TEST(ScenarioErrors, WrongType) {
  ExpectInputError({With(14, "  laps: two"), 14, "robot.laps must be an integer, got 'two'"});
  ExpectInputError({With(14, "  laps: 1.5"), 14, "robot.laps must be an integer"});
  ExpectInputError({With(16, "  odometry: {rate_hz: fast}"), 16, "sensors.odometry.rate_hz must be a number"});
  ExpectInputError({With(16, "  odometry: {rate_hz: [50]}"), 16, "must be a number, not a list"});
  ExpectInputError({With(18, "  landmarks: {known_ids: maybe}"), 18, "must be true or false"});
  ExpectInputError({With(12, "  start: [1, 1]"), 12, "robot.start must be a mapping"});
  ExpectInputError({With(13, "  path: [[9, 1], [9]]"), 13, "robot.path[1] must be a point [x, y]"});
  ExpectInputError({With(16, "  odometry: {alpha: [0.1, 0.1]}"), 16, "alpha must be a list of 4 numbers"});
  ExpectInputError({With(6, "    - box: {center: [5, 5], size: [0, 1]}"), 6, "size must be positive"});
  ExpectInputError({With(14, "  laps: .inf"), 14, "must be an integer"});
  ExpectInputError({With(12, "  start: {x: .nan, y: 1}"), 12, "robot.start.x must be finite"});
}

TEST(ScenarioErrors, OutOfRange) {
  ExpectInputError({With(17, "  lidar: {rate_hz: -1}"), 17, "sensors.lidar.rate_hz = -1 is out of range"}, "> 0");
  ExpectInputError({With(16, "  odometry: {rate_hz: 0}"), 16, "sensors.odometry.rate_hz = 0 is out of range"});
  ExpectInputError({With(18, "  gyro: {rate_hz: -10}"), 18, "sensors.gyro.rate_hz = -10 is out of range"}, ">= 0");
  ExpectInputError({With(17, "  lidar: {dropout_prob: 1.5}"), 17, "dropout_prob = 1.5 is out of range"}, ">= 0 and <= 1");
  ExpectInputError({With(18, "  landmarks: {detection_prob: -0.1}"), 18, "detection_prob = -0.1 is out of range"});
  ExpectInputError({With(17, "  lidar: {beams: 0}"), 17, "sensors.lidar.beams = 0 is out of range"}, ">= 1");
  ExpectInputError({With(17, "  lidar: {fov_deg: 0}"), 17, "fov_deg = 0 is out of range"}, "> 0 and <= 360");
  ExpectInputError({With(17, "  lidar: {fov_deg: 361}"), 17, "fov_deg = 361 is out of range"});
  ExpectInputError({With(18, "  landmarks: {fov_deg: -5}"), 18, "fov_deg = -5 is out of range"});
  ExpectInputError({With(17, "  lidar: {range_min_m: 5, range_max_m: 4}"), 17, "range_max_m = 4 is out of range"});
  ExpectInputError({With(17, "  lidar: {sigma_range_m: -0.01}"), 17, "sigma_range_m = -0.01 is out of range"});
  ExpectInputError({With(14, "  laps: 0"), 14, "robot.laps = 0 is out of range"}, ">= 1");
  ExpectInputError({With(14, "  radius_m: 0"), 14, "robot.radius_m = 0 is out of range"});
  ExpectInputError({With(9, "    - {pos: [2, 8], radius_m: -1}"), 9, "radius_m = -1 is out of range"});
  ExpectInputError({With(2, "duration_s: -3"), 2, "duration_s = -3 is out of range"});
}

TEST(ScenarioErrors, RequiredKeysAndVersion) {
  // A block mapping's line is its first key's: here robot's `start:` line.
  ExpectInputError({With(13, "  radius_m: 0.25"), 12, "missing required key 'robot.path'"}, "path:");
  ExpectInputError({With(1, "# no version"), 2, "missing required key 'version'"}, "version: 1");
  ExpectInputError({With(1, "version: 2"), 1, "unsupported scenario version 2"}, "version: 1");
  ExpectInputError({With(6, "    - box: {center: [5, 5]}"), 6, "missing required key 'world.walls[1].box.size'"});
  ExpectInputError({With(10, "  movers:\n    - {circle: {radius_m: 0.3}}"), 11, "missing required key 'world.movers[0].path'"});
  ExpectInputError({With(10, "  movers:\n    - {path: [[1, 5], [3, 5]]}"), 11, "exactly one shape"});
}

TEST(ScenarioErrors, DuplicateKey) {
  ExpectInputError({With(14, "  laps: 1\n  laps: 2"), 15, "duplicate key 'laps' in robot"}, "keep one");
  ExpectInputError({With(17, "  lidar: {beams: 180, beams: 90}"), 17, "duplicate key 'beams' in sensors.lidar"});
}

TEST(ScenarioErrors, MissingRobotOrEmptyPath) {
  ExpectInputError({"version: 1\nname: x\n", 1, "missing required key 'robot'"}, "robot:");
  ExpectInputError({With(13, "  path: []"), 13, "robot.path must be a list of one or more points"}, "[[x, y]");
  ExpectInputError({With(13, "  path: [[9, 1], [9, x]]"), 13, "robot.path[1][1] must be a number, got 'x'"});
}

TEST(ScenarioErrors, DuplicateLandmarkId) {
  ExpectInputError({With(10, "    - {pos: [3, 8], id: 0}"), 10, "duplicate landmark id 0"}, "distinct id");
}

TEST(ScenarioErrors, RobotStartInsideGeometry) {
  ExpectInputError({With(12, "  start: {x: 0.1, y: 1}"), 12, "robot start (0.1, 1) is inside or too close to the polygon wall at line 5"});
  ExpectInputError({With(12, "  start: {x: 5.2, y: 4.9}"), 12, "inside or too close to the box at line 6"}, "move robot.start");
  ExpectInputError({With(12, "  start: {x: 5.7, y: 5}"), 12, "the box at line 6"});  // outside, within radius
  ExpectInputError({With(12, "  start: {x: 8, y: 8.1}"), 12, "the circle at line 7"});
  ExpectInputError({With(12, "  start: {x: 2, y: 8.2}"), 12, "the landmark post 0 at line 9"});
  ExpectInputError({With(14, "  laps: 1\n  kidnap: {at_s: 5, to: {x: 5, y: 5}}"), 15, "kidnap target (5, 5) is inside"});
}

TEST(ScenarioErrors, UnreachableWaypoint) {
  // Through the box (waypoint 1 at line 15).
  ExpectInputError({With(13, "  path:\n    - [9, 1]\n    - [1, 9]"), 15,
                    "waypoint 1 (1, 9) unreachable: the straight drive from (9, 1) comes within robot.radius_m (0.25 m) of the box at line 6"},
                   "add one in between");
  // Grazing the circle: 0.2 m from its rim, less than the robot's radius.
  ExpectInputError({With(13, "  path: [[8.7, 1], [8.7, 9.5]]"), 13, "waypoint 1 (8.7, 9.5) unreachable"});
  // Start -> first waypoint leaves the room.
  ExpectInputError({With(13, "  path: [[12, 1]]"), 13, "waypoint 0 (12, 1) unreachable"});
  // The closing leg (last -> first) only matters when the path is driven more than once.
  const std::string closing = "  path: [[1, 9], [9, 9], [9, 1]]";
  testing::TempDir dir;
  EXPECT_NO_THROW(LoadScenario(dir.Write("one_lap.yaml", With(13, closing))));
  std::string two_laps = With(13, closing);
  two_laps.replace(two_laps.find("laps: 1"), 7, "laps: 2");
  ExpectInputError({two_laps, 13, "waypoint 0 (1, 9) unreachable: the straight drive from (9, 1)"});
}

TEST(ScenarioErrors, MoverPathIntoWall) {
  ExpectInputError({With(10, "  movers:\n    - {box: {size: [0.8, 0.5]}, path: [[1, 5], [6, 5]]}"), 11,
                    "mover 0's path from (1, 5) to (6, 5) runs into the box at line 6"});
}

TEST(ScenarioErrors, EmptyFileAndGarbage) {
  ExpectInputError({"", 0, "the scenario is empty"}, "version: 1");
  ExpectInputError({"# only a comment\n", 0, "the scenario is empty"});
  ExpectInputError({"version: 1\nname: [unclosed\nrobot: {}\n", 3, "not valid YAML"}, "fix the syntax");
  ExpectInputError({"version: 1\n  bad indent: 2\n", 2, "not valid YAML"});
  ExpectInputError({"- 1\n- 2\n", 1, "a scenario must be a YAML mapping, got a list"});
  ExpectInputError({"just some words\n", 1, "a scenario must be a YAML mapping, got plain text"});
  ExpectInputError({std::string("\x01\x02\xff binary", 10), 1, "must be a YAML mapping"});
}

TEST(ScenarioErrors, NoSuchScenario) {
  try {
    LoadScenario("no_such_scenario_or_file.yaml");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no such scenario file or built-in"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("loop, maze"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace slambox

namespace slambox {
namespace {

// Robustness: random edits of valid scenario text either load or throw InputError;
// no other exception escapes (yaml-cpp's own exceptions are all translated).
TEST(ScenarioErrors, RandomEditsGiveInputErrorsOnly) {
  std::mt19937_64 rng(42);
  const std::string alphabet = " :-[]{},.0a#\n\t\"'&*!|>";
  int errors = 0, loaded = 0;
  for (const auto& b : BuiltinScenarios()) {
    const std::string text = ScenarioToYaml(LoadScenario(b.name));
    for (int trial = 0; trial < 60; ++trial) {
      std::string edited = text;
      const int edits = 1 + static_cast<int>(rng() % 3);
      for (int e = 0; e < edits; ++e) {
        const std::size_t at = rng() % edited.size();
        switch (rng() % 3) {
          case 0: edited.erase(at, 1 + rng() % 8); break;
          case 1: edited.insert(at, 1, alphabet[rng() % alphabet.size()]); break;
          default: edited[at] = alphabet[rng() % alphabet.size()]; break;
        }
      }
      try {
        LoadScenarioText(edited, "edited", {});
        ++loaded;
      } catch (const InputError& e) {
        ++errors;
        EXPECT_NE(std::string(e.what()).find("fix: "), std::string::npos) << e.what();
      } catch (const std::exception& e) {
        ADD_FAILURE() << "non-InputError " << e.what() << " for:\n" << edited;
      }
    }
  }
  EXPECT_GT(errors, 50);  // the edits do break files; the test exercises the error paths
  EXPECT_GT(loaded, 10);
}

}  // namespace
}  // namespace slambox
