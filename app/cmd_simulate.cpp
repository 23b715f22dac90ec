// `slambox simulate`: scenario + seed -> stream file, with a one-line summary on stderr.
#include <iostream>
#include <memory>
#include <sstream>

#include "app/commands.hpp"
#include "app/simulate_command.hpp"
#include "core/error.hpp"
#include "core/stream_io.hpp"

namespace slambox {

SimulateSummary SimulateToFile(const SimulateRequest& request) {
  for (const std::string& set : request.sets) {
    if (set.rfind("algo.", 0) == 0)
      throw InputError("--set " + set, 0, "algorithm parameters do not apply to `slambox simulate`",
                       "pass algo.* keys to `slambox run` or `slambox sweep`; simulate takes scenario keys only");
    if (set.find('=') == std::string::npos)
      throw InputError("--set " + set, 0, "expected KEY=VALUE", "write e.g. --set sensors.lidar.sigma_range_m=0.05");
  }
  if (IsStreamFile(request.input))
    throw InputError(request.input, 0, "this is already a stream file; simulate takes a scenario",
                     "give a built-in scenario name or a scenario YAML file (use the stream with `slambox run`)");
  const Scenario scenario = LoadScenario(request.input, request.sets);
  SimulateSummary out;
  out.stream = Simulate(scenario, request.seed, {}, &out.report);
  WriteStream(out.stream, request.output);

  long odometry = 0, scans = 0, landmarks = 0, gyro = 0;
  for (const SensorEvent& e : out.stream.events) {
    odometry += std::holds_alternative<OdometryEvent>(e);
    scans += std::holds_alternative<LaserScanEvent>(e);
    landmarks += std::holds_alternative<LandmarkEvent>(e);
    gyro += std::holds_alternative<GyroEvent>(e);
  }
  std::ostringstream line;
  line.setf(std::ios::fixed);
  line.precision(1);
  line << "simulated " << scenario.name << " (seed " << request.seed << "): " << out.stream.header.duration_s << " s, "
       << out.report.distance_m << " m, " << odometry << " odometry, " << scans << " scans, " << landmarks
       << " landmark, " << gyro << " gyro events, " << out.report.wall_contacts << " wall contacts -> "
       << request.output;
  out.line = line.str();
  return out;
}

void AddSimulateCommand(CLI::App& app) {
  auto request = std::make_shared<SimulateRequest>();
  CLI::App* cmd = app.add_subcommand("simulate", "simulate a scenario once and write its sensor stream file");
  cmd->add_option("scenario", request->input, "built-in scenario name or scenario YAML file")->required();
  cmd->add_option("--seed", request->seed, "random seed of every noise source (default 0)");
  cmd->add_option("--set", request->sets, "override a scenario key, e.g. --set robot.laps=3 (repeatable)");
  cmd->add_option("-o,--output", request->output, "stream file to write")->required();
  cmd->callback([request] { std::cerr << SimulateToFile(*request).line << "\n"; });
}

}  // namespace slambox
