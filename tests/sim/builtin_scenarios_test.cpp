// Every built-in scenario's path is driven to its end without touching a wall.
#include <gtest/gtest.h>

#include "sim/scenario.hpp"
#include "sim/simulate.hpp"

namespace slambox {
namespace {

class BuiltinScenarioPath : public ::testing::TestWithParam<std::string> {};

TEST_P(BuiltinScenarioPath, DrivenWithoutCollision) {
  Scenario scenario = LoadScenario(GetParam());
  scenario.sensors = SensorSuite{};  // the path is what is tested here; sensors cost time
  SimulationReport report;
  const Stream stream = Simulate(scenario, 0, {}, &report);
  if (scenario.duration_s == 0.0) {
    EXPECT_TRUE(report.path_completed);
    const Eigen::Vector2d last = scenario.robot.path.back();
    EXPECT_LT((stream.groundtruth.back().pose.translation() - last).norm(), 0.05);
  }
  EXPECT_EQ(report.wall_contacts, 0) << GetParam();
  EXPECT_GT(report.distance_m, 10.0);
  std::printf("%s: %.1f s, %.1f m, %d mover contacts\n", GetParam().c_str(), stream.header.duration_s,
              report.distance_m, report.mover_contacts);
}

/// The built-in scenarios of DESIGN.md, and `office` (its world a ROS map image).
std::vector<std::string> Names() {
  return {"loop", "tunnel", "landmarks", "forest", "maze", "dynamic", "symmetric", "office"};
}

INSTANTIATE_TEST_SUITE_P(All, BuiltinScenarioPath, ::testing::ValuesIn(Names()),
                         [](const auto& info) { return info.param; });

TEST(BuiltinScenarios, AllArePresent) {
  for (const std::string& name : Names()) {
    bool found = false;
    for (const auto& b : BuiltinScenarios()) found = found || b.name == name;
    EXPECT_TRUE(found) << name;
  }
}

}  // namespace
}  // namespace slambox
