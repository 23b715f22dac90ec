// `slambox scenarios`, `slambox scenario show`, `slambox algorithms [--params NAME]`:
// what can be simulated and what can be run, printed as plain text on stdout.
#include <algorithm>
#include <array>
#include <iomanip>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "app/exec_module.hpp"
#include "app/registry.hpp"
#include "core/stream_io.hpp"
#include "sim/scenario.hpp"
#include "sim/scenario_limits.hpp"

namespace slambox {
namespace {

std::string Needs(const SensorNeeds& needs) {
  std::string out;
  auto add = [&](bool on, const char* name) {
    if (on) out += (out.empty() ? "" : "+") + std::string(name);
  };
  add(needs.odometry, "odometry");
  add(needs.lidar, "lidar");
  add(needs.landmarks, "landmarks");
  add(needs.map, "map");
  return "[" + (out.empty() ? std::string("-") : out) + "]";
}

void PrintScenarios() {
  const std::vector<BuiltinScenario> all = BuiltinScenarios();
  std::size_t width = 0;
  for (const auto& s : all) width = std::max(width, s.name.size());
  for (const auto& s : all) std::cout << std::left << std::setw(static_cast<int>(width) + 2) << s.name << s.description << "\n";
}

// Plugin modules say which plugin they come from; a shipped plugin is not loaded for this.
void PrintAlgorithms() {
  const std::vector<ModuleListing> all = ListModules();
  std::size_t name_w = 0, needs_w = 0;
  for (const auto& m : all) {
    name_w = std::max(name_w, m.name.size());
    needs_w = std::max(needs_w, Needs(m.needs).size());
  }
  const std::vector<const ModuleInfo*> exec = ExecModulesOnPath();  // declared on $SLAMBOX_EXEC_PATH
  for (const ModuleInfo* m : exec) {
    name_w = std::max(name_w, m->name.size());
    needs_w = std::max(needs_w, Needs(m->needs).size());
  }
  for (const auto& m : all) {
    std::cout << std::left << std::setw(static_cast<int>(name_w) + 2) << m.name
              << std::setw(static_cast<int>(needs_w) + 2) << Needs(m.needs) << m.description;
    if (!m.origin.empty()) std::cout << " (" << m.origin << ")";
    if (!m.in_all) std::cout << " (named only, not in all)";
    if (!m.unavailable.empty()) std::cout << " [unavailable: " << m.unavailable << "]";
    std::cout << "\n";
  }
  for (const ModuleInfo* m : exec)
    std::cout << std::left << std::setw(static_cast<int>(name_w) + 2) << m->name
              << std::setw(static_cast<int>(needs_w) + 2) << Needs(m->needs) << m->description << " (exec)\n";
}

void PrintParams(const std::string& module_name) {
  const ModuleInfo& module = FindModule(module_name);  // InputError listing the names
  const std::vector<ParamInfo> params = module.params();
  if (params.empty()) {
    std::cout << module.name << " has no parameters\n";
    return;
  }
  std::vector<std::array<std::string, 5>> rows = {{"name", "type", "default", "unit", "meaning"}};
  for (const auto& p : params) rows.push_back({"algo." + module.name + "." + p.name, p.type, p.default_value, p.unit, p.meaning});
  std::array<std::size_t, 4> w{};
  for (const auto& r : rows)
    for (std::size_t c = 0; c < 4; ++c) w[c] = std::max(w[c], r[c].size());
  for (const auto& r : rows) {
    for (std::size_t c = 0; c < 4; ++c) std::cout << std::left << std::setw(static_cast<int>(w[c]) + 2) << r[c];
    std::cout << r[4] << "\n";
  }
}

}  // namespace

void AddScenarioCommands(CLI::App& app) {
  CLI::App* scenarios = app.add_subcommand("scenarios", "List the built-in scenarios, one line each: name, what it tests");
  scenarios->callback(PrintScenarios);

  CLI::App* scenario = app.add_subcommand("scenario", "Inspect a scenario");
  scenario->require_subcommand(1);
  CLI::App* show = scenario->add_subcommand(
      "show", "Print a scenario (built-in name or YAML file) with every default filled in and overrides applied");
  auto target = std::make_shared<std::string>();
  auto overrides = std::make_shared<std::vector<std::string>>();
  show->add_option("scenario", *target,
                   "built-in scenario name (see `slambox scenarios`), a .yaml file, or a stream file (its scenario)")
      ->required();
  show->add_option("--set", *overrides, "override a scenario key, e.g. --set robot.laps=3 (repeatable)")
      ->type_name("KEY=VALUE");
  show->callback([target, overrides] {
    // A stream carries the resolved scenario it was simulated from.
    const Scenario scenario =
        IsStreamFile(*target)
            ? LoadScenarioText(ReadStream(*target).header.scenario_yaml, *target + " (scenario in the stream header)",
                               *overrides)
            : LoadScenario(*target, *overrides);
    std::cout << ScenarioToYaml(scenario);
    std::cout << "# " << DescribeStreamSize(EstimateStreamSize(scenario)) << "\n";  // a comment: still valid YAML
  });

  CLI::App* algorithms = app.add_subcommand(
      "algorithms", "List the registered SLAM modules (name, sensors needed, description), or one module's parameters");
  auto params_of = std::make_shared<std::string>();
  auto plugins = std::make_shared<std::vector<std::string>>();
  algorithms->add_option("--plugin", *plugins, "also list the modules of this module plugin (repeatable)")
      ->type_name("PATH.so");
  algorithms->add_option("--params", *params_of,
                         "list the parameters of module NAME (settable as --set algo.NAME.FIELD=VALUE) with "
                         "type, default, unit and meaning")
      ->type_name("NAME");
  algorithms->callback([params_of, plugins] {
    for (const auto& p : *plugins) LoadPlugin(p);
    if (params_of->empty())
      PrintAlgorithms();
    else
      PrintParams(*params_of);
  });
}

}  // namespace slambox
