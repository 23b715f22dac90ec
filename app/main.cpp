// slambox: simulate, run and judge 2D SLAM algorithms from the command line.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>

#include "app/commands.hpp"
#include "core/error.hpp"
#include "core/version.hpp"

int main(int argc, char** argv) {
  CLI::App app{"slambox: simulate, run and judge 2D SLAM algorithms"};
  app.set_version_flag("--version", std::string("slambox ") + slambox::kVersion);
  app.require_subcommand(1);
  slambox::AddScenarioCommands(app);
  slambox::AddSimulateCommand(app);
  slambox::AddRunCommand(app);
  slambox::AddEvalCommand(app);
  slambox::AddReportCommand(app);
  slambox::AddOptimizeCommand(app);
  slambox::AddSweepCommand(app);
  slambox::AddConvertCommand(app);
  slambox::AddExportCommand(app);
  slambox::AddExecCheckCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const slambox::CommandExit& e) {
    return e.code;
  } catch (const slambox::InputError& e) {
    std::cerr << "slambox: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "slambox: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
