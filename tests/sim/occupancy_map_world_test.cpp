// A scenario world from a ROS map image (`world: {occupancy_map: FILE.yaml}`): the path
// resolves relative to the scenario file, the LIDAR sees exactly the grid's occupied cells
// (against the per-cell brute force), Box2D stops the robot at them, and poses and
// waypoints in occupied cells are errors naming the line.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "core/ros_map.hpp"
#include "core/stream_io.hpp"
#include "sim/box2d_world.hpp"
#include "sim/grid_ray_cast.hpp"
#include "sim/scenario.hpp"
#include "sim/simulate.hpp"

namespace slambox {
namespace {

namespace fs = std::filesystem;

// 10 m x 8 m room at 0.05 m: walls 3 cells thick on the border, a 1 m x 0.5 m pillar.
OccupancyGrid Room() {
  OccupancyGrid g;
  g.resolution_m = 0.05;
  g.origin_m = {-1.0, -2.0};
  g.width = 200;
  g.height = 160;
  g.cells.assign(std::size_t(g.width) * g.height, 0);
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      const bool border = x < 3 || y < 3 || x >= g.width - 3 || y >= g.height - 3;
      const bool pillar = x >= 100 && x < 120 && y >= 70 && y < 80;  // x [4, 5), y [1.5, 2.0)
      if (border || pillar) g.cells[std::size_t(y) * g.width + x] = 100;
      if (x >= 150 && y >= 120 && !border) g.cells[std::size_t(y) * g.width + x] = -1;  // unknown corner
    }
  return g;
}

class OccupancyMapWorld : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("slambox_map_world_" + std::to_string(::getpid()));
    fs::create_directories(dir_ / "maps");
    WriteRosMap((dir_ / "maps" / "room.yaml").string(), Room());
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Scenario(const std::string& path_yaml, const std::string& extra = "") {
    const fs::path p = dir_ / "room_scenario.yaml";
    std::ofstream(p) << "version: 1\nname: room\nworld:\n  occupancy_map: maps/room.yaml\n" << extra
                     << "robot:\n  start: {x: 0, y: -1, theta_deg: 0}\n  path: " << path_yaml << "\n"
                     << "sensors:\n  odometry: {rate_hz: 50}\n"
                     << "  lidar: {rate_hz: 10, beams: 90, range_max_m: 30, sigma_range_m: 0}\n";
    return p.string();
  }
  fs::path dir_;
};

TEST_F(OccupancyMapWorld, PathResolvesBesideTheScenarioAndShowRoundTrips) {
  const auto s = LoadScenario(Scenario("[[7, -1], [7, 4], [0, 4]]"));
  EXPECT_EQ(fs::path(s.occupancy_map), fs::absolute(dir_ / "maps" / "room.yaml").lexically_normal());
  EXPECT_EQ(s.occupancy_grid.cells, Room().cells);
  const std::string yaml = ScenarioToYaml(s);
  EXPECT_NE(yaml.find("occupancy_map: " + s.occupancy_map), std::string::npos) << yaml;
  const auto again = LoadScenarioText(yaml, "shown");
  EXPECT_EQ(again.occupancy_grid.cells, s.occupancy_grid.cells);
  const World w = MakeWorld(s);
  EXPECT_EQ(w.wall_segments.size(), 4u + 4u + 4u) << "outer and inner border loops and the pillar";
}

TEST_F(OccupancyMapWorld, LidarSeesExactlyTheOccupiedCells) {
  const auto s = LoadScenario(Scenario("[[7, -1], [7, 4], [0, 4]]"));
  const Stream stream = Simulate(s, 0);
  const OccupancyGrid grid = Room();
  const GridRayCaster caster(grid);
  int scans = 0, checked = 0;
  std::size_t g = 0;
  for (const auto& e : stream.events) {
    const auto* scan = std::get_if<LaserScanEvent>(&e);
    if (!scan) continue;
    while (g < stream.groundtruth.size() && stream.groundtruth[g].t_s < scan->t_s - 1e-9) ++g;
    ASSERT_LT(g, stream.groundtruth.size());
    ASSERT_NEAR(stream.groundtruth[g].t_s, scan->t_s, 1e-9);
    const SE2& T = stream.groundtruth[g].pose;
    for (std::size_t i = 0; i < scan->ranges_m.size(); ++i) {
      const double a = scan->angle_min_rad + double(i) * scan->angle_increment_rad;
      const Eigen::Vector2d dir = T.rotation() * Eigen::Vector2d(std::cos(a), std::sin(a));
      const double truth = caster.CastBruteForce(T.translation(), dir, scan->range_max_m);
      ASSERT_EQ(scan->valid[i] != 0, std::isfinite(truth)) << "scan " << scans << " beam " << i;
      if (scan->valid[i]) {
        EXPECT_NEAR(scan->ranges_m[i], truth, 1e-9) << "scan " << scans << " beam " << i;
      }
      ++checked;
    }
    if (++scans == 40) break;
  }
  EXPECT_EQ(checked, 40 * 90);
}

TEST_F(OccupancyMapWorld, RobotStopsAtOccupiedCells) {
  const auto s = LoadScenario(Scenario("[[3, -1]]"));
  const World world = MakeWorld(s);
  PhysicsWorld physics(s, world);
  // Drive straight at the pillar's west face (x = 4) from (0, 1.75) for 10 s at 1 m/s.
  physics.TeleportRobot(SE2(0.0, 1.75, 0.0));
  double t = 0.0;
  for (int k = 0; k < 500; ++k) {
    physics.SetRobotVelocity(1.0, 0.0);
    physics.Step(0.02, t += 0.02);
    ASSERT_LT(physics.RobotPose().x, 4.0 - s.robot.radius_m + 0.02) << "the disc entered the pillar at t " << t;
  }
  EXPECT_GT(physics.RobotPose().x, 4.0 - s.robot.radius_m - 0.02) << "it drove up to the face";
  EXPECT_GT(physics.contacts().robot_wall, 0);
}

TEST_F(OccupancyMapWorld, PosesInOccupiedCellsAreErrors) {
  auto error_of = [](const std::string& path) {
    try {
      LoadScenario(path);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  std::string e = error_of(Scenario("[[4.5, 1.75]]"));  // inside the pillar
  EXPECT_NE(e.find("waypoint 0 (4.5, 1.75) is in an occupied cell of world.occupancy_map"), std::string::npos) << e;
  EXPECT_NE(e.find("room_scenario.yaml:"), std::string::npos) << e;
  e = error_of(Scenario("[[8, 3.5]]"));  // the leg from the start crosses the pillar at x = 4.4 .. 5
  EXPECT_NE(e.find("occupied cells of world.occupancy_map"), std::string::npos) << e;
  fs::remove(dir_ / "maps" / "room.pgm");
  e = error_of(Scenario("[[7, -1]]"));
  EXPECT_NE(e.find("world.occupancy_map: "), std::string::npos) << e;
  EXPECT_NE(e.find("room.pgm"), std::string::npos) << e;
  EXPECT_NE(e.find("room_scenario.yaml:4"), std::string::npos) << e;
}

TEST(OccupancyMapExample, BuiltinOfficeIsTheCommittedMapImage) {
  const fs::path dir = fs::temp_directory_path() / ("slambox_office_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  auto WriteTemp = [&](const std::string& name, const std::string& text) {
    std::ofstream((dir / name).string()) << text;
    return (dir / name).string();
  };
  // The built-in reads the embedded copies of scenarios/maps/office_map.{yaml,pgm}; the file
  // scenarios/office.yaml reads them from disk: the same grid, the same stream.
  const auto builtin = LoadScenario("office");
  const auto file = LoadScenario(std::string(SLAMBOX_SOURCE_DIR) + "/scenarios/office.yaml");
  EXPECT_EQ(builtin.source, "builtin:office");
  EXPECT_EQ(builtin.occupancy_map, "builtin:maps/office_map.yaml");
  EXPECT_EQ(file.occupancy_map, std::string(SLAMBOX_SOURCE_DIR) + "/scenarios/maps/office_map.yaml");
  EXPECT_EQ(builtin.occupancy_grid.width, 320);
  EXPECT_EQ(builtin.occupancy_grid.height, 200);
  EXPECT_EQ(builtin.occupancy_grid.cells, file.occupancy_grid.cells);
  EXPECT_EQ(builtin.occupancy_grid.origin_m, file.occupancy_grid.origin_m);
  EXPECT_GT(std::count(builtin.occupancy_grid.cells.begin(), builtin.occupancy_grid.cells.end(), 100), 1000);
  SimulationReport report;
  Scenario short_builtin = builtin, short_file = file;
  short_builtin.duration_s = short_file.duration_s = 20.0;
  Stream from_builtin = Simulate(short_builtin, 3, {}, &report), from_file = Simulate(short_file, 3);
  from_file.header.scenario_yaml = from_builtin.header.scenario_yaml;  // it names the map's path
  EXPECT_EQ(SerializeStream(from_builtin), SerializeStream(from_file));
  EXPECT_EQ(report.wall_contacts, 0);
  // `scenario show`'s path (builtin:maps/...) reads back from any file, and a wrong name says what exists.
  const auto shown = WriteTemp("shown.yaml", ScenarioToYaml(builtin));
  EXPECT_EQ(LoadScenario(shown).occupancy_grid.cells, builtin.occupancy_grid.cells);
  std::string text = ScenarioToYaml(builtin);
  text.replace(text.find("builtin:maps/office_map.yaml"), 28, "builtin:maps/no_such_map.yaml");
  try {
    LoadScenario(WriteTemp("bad.yaml", text));
    ADD_FAILURE() << "a missing built-in map file was accepted";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("no such built-in map file"), std::string::npos) << m;
    EXPECT_NE(m.find("maps/office_map.yaml"), std::string::npos) << m;
    EXPECT_NE(m.find("bad.yaml:"), std::string::npos) << m;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace slambox
