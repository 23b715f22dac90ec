#pragma once
// Each `slambox` subcommand registers itself on the CLI11 app; main() calls these.
#include <CLI/CLI.hpp>
#include <map>
#include <string>

#include "core/params.hpp"

namespace slambox {

/// An option's transformer for an enum by its user-facing names (case-insensitive); --help
/// lists them as {a,b,c}.
template <typename Enum>
CLI::CheckedTransformer EnumTransformer(const EnumNames<Enum>& names) {
  std::map<std::string, Enum> by_name;
  std::string listed;
  for (const auto& [value, name] : names) by_name[name] = value, listed += (listed.empty() ? "" : ",") + std::string(name);
  CLI::CheckedTransformer t(by_name, CLI::ignore_case);
  t.description("{" + listed + "}");
  return t;
}

/// Thrown by a command that must end with a non-zero exit after printing its own
/// message (e.g. a failed regression check); main() returns `code`.
struct CommandExit {
  int code = 1;
};

void AddScenarioCommands(CLI::App& app);   // scenarios, scenario show, algorithms
void AddSimulateCommand(CLI::App& app);    // simulate
void AddRunCommand(CLI::App& app);         // run
void AddEvalCommand(CLI::App& app);        // eval
void AddReportCommand(CLI::App& app);      // report
void AddOptimizeCommand(CLI::App& app);    // optimize
void AddSweepCommand(CLI::App& app);       // sweep
void AddConvertCommand(CLI::App& app);     // convert carmen
void AddExportCommand(CLI::App& app);      // export (stream as JSON Lines / CSV)
void AddExecCheckCommand(CLI::App& app);   // exec-check (exec protocol conformance)

}  // namespace slambox
