// `slambox scenarios`, `scenario show`, `algorithms [--params]` through the CLI11 app.
#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>

#include "app/commands.hpp"
#include "app/registry.hpp"
#include "core/error.hpp"
#include "core/stream_io.hpp"
#include "sim/scenario.hpp"

namespace slambox {
namespace {

/// Runs the scenario commands with `args` and returns what they print on stdout.
std::string RunCommand(std::vector<std::string> args) {
  CLI::App app{"slambox"};
  app.require_subcommand(1);
  AddScenarioCommands(app);
  args.insert(args.begin(), "slambox");
  std::vector<const char*> argv;
  for (const auto& a : args) argv.push_back(a.c_str());
  std::ostringstream captured;
  std::streambuf* old = std::cout.rdbuf(captured.rdbuf());
  try {
    app.parse(static_cast<int>(argv.size()), argv.data());
  } catch (...) {
    std::cout.rdbuf(old);
    throw;
  }
  std::cout.rdbuf(old);
  return captured.str();
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(CmdScenario, ScenariosPrintsOneLineEach) {
  const auto lines = Lines(RunCommand({"scenarios"}));
  const auto builtins = BuiltinScenarios();
  ASSERT_EQ(lines.size(), builtins.size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    EXPECT_EQ(lines[i].rfind(builtins[i].name + " ", 0), 0u) << lines[i];
    EXPECT_NE(lines[i].find(builtins[i].description), std::string::npos) << lines[i];
  }
}

TEST(CmdScenario, ShowPrintsTheResolvedScenarioWithOverrides) {
  const std::string out = RunCommand({"scenario", "show", "tunnel", "--set", "robot.laps=3", "--set", "sensors.lidar.beams=90"});
  // The resolved YAML, then the memory estimate as a comment (sim/scenario_limits.hpp).
  const std::string yaml = ScenarioToYaml(LoadScenario("tunnel", {"robot.laps=3", "sensors.lidar.beams=90"}));
  EXPECT_EQ(out.substr(0, yaml.size()), yaml);
  EXPECT_EQ(out.rfind("\n# stream estimate", yaml.size() - 1), yaml.size() - 1) << out;
  EXPECT_NE(out.find("laps: 3"), std::string::npos);
  EXPECT_NE(out.find("beams: 90"), std::string::npos);
  EXPECT_THROW(RunCommand({"scenario", "show", "tunnel", "--set", "robot.lapz=3"}), InputError);
  EXPECT_THROW(RunCommand({"scenario", "show", "no-such-scenario"}), InputError);
  EXPECT_THROW(RunCommand({"scenario", "show"}), CLI::RequiredError);
  EXPECT_THROW(RunCommand({"scenario"}), CLI::RequiredError);
}

TEST(CmdScenario, ShowReadsTheScenarioOfAStream) {
  Stream stream;
  stream.header.scenario_name = "tunnel";
  stream.header.scenario_yaml = ScenarioToYaml(LoadScenario("tunnel"));
  const std::string path = ::testing::TempDir() + "/cmd_scenario_show.stream";
  WriteStream(stream, path);
  const std::string shown = RunCommand({"scenario", "show", path});
  EXPECT_EQ(shown.substr(0, stream.header.scenario_yaml.size()), stream.header.scenario_yaml);
  EXPECT_NE(RunCommand({"scenario", "show", path, "--set", "robot.laps=2"}).find("laps: 2"), std::string::npos);
  std::remove(path.c_str());
}

TEST(CmdScenario, AlgorithmsListsModulesAndParams) {
  const auto lines = Lines(RunCommand({"algorithms"}));
  const auto listed = ListModules();  // built-ins, then the shipped plugins' (not loaded)
  ASSERT_EQ(lines.size(), listed.size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    EXPECT_EQ(lines[i].rfind(listed[i].name + " ", 0), 0u) << lines[i];
    EXPECT_NE(lines[i].find(listed[i].description), std::string::npos) << lines[i];
  }
  EXPECT_NE(RunCommand({"algorithms"}).find("odometry  "), std::string::npos);

  const std::string params = RunCommand({"algorithms", "--params", "odometry"});
  const auto rows = Lines(params);
  const auto infos = FindModule("odometry").params();
  ASSERT_EQ(rows.size(), infos.size() + 1);  // header + one row each
  for (const char* col : {"name", "type", "default", "unit", "meaning"}) EXPECT_NE(rows[0].find(col), std::string::npos);
  for (std::size_t i = 0; i < infos.size(); ++i) {
    EXPECT_EQ(rows[i + 1].rfind("algo.odometry." + infos[i].name, 0), 0u) << rows[i + 1];
    for (const auto& field : {infos[i].type, infos[i].default_value, infos[i].meaning})
      EXPECT_NE(rows[i + 1].find(field), std::string::npos) << rows[i + 1];
  }
  EXPECT_THROW(RunCommand({"algorithms", "--params", "no-such-module"}), InputError);
}

TEST(Registry, EveryModuleBuildsWithItsDefaultsAndRejectsAnOutOfRangeValue) {
  for (const auto& m : AllModules()) EXPECT_NO_THROW(m.create({})) << m.name << ": a default is outside its range";
  try {
    FindModule("icp-odometry").create({{"trim_fraction", "1"}});
    FAIL() << "trim_fraction = 1 accepted";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("--set algo.icp-odometry.trim_fraction"), std::string::npos) << msg;
    EXPECT_NE(msg.find(">= 0 and < 1"), std::string::npos) << msg;
  }
}

TEST(CmdScenario, EveryCommandHasHelp) {
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"scenarios", "--help"}, {"scenario", "--help"}, {"scenario", "show", "--help"}, {"algorithms", "--help"}})
    EXPECT_THROW(RunCommand(args), CLI::CallForHelp) << args[0];
}

}  // namespace
}  // namespace slambox
