// `slambox run NAME|FILE|STREAM [--algo A,B,...] [--seed N] [--set k=v]... -o DIR`
#include <iostream>

#include "app/commands.hpp"
#include "app/exec_module.hpp"
#include "app/run.hpp"
#include "core/error.hpp"

namespace slambox {

void AddRunCommand(CLI::App& app) {
  auto request = std::make_shared<RunRequest>();
  auto* cmd = app.add_subcommand("run", "replay a scenario or stream to SLAM modules, score and draw them");
  cmd->add_option("input", request->input, "built-in scenario name, scenario YAML file, or stream file")->required();
  cmd->add_option("--algo", request->algorithms, "modules to run (comma-separated), or all")
      ->delimiter(',')
      ->default_str("odometry");
  cmd->add_option("--plugin", request->plugins, "load a module plugin first (repeatable; see docs/plugins.md)")
      ->type_name("PATH.so");
  cmd->add_option("--seed", request->seed, "simulation seed (scenarios only)")
      ->each([request](const std::string&) { request->seed_given = true; });
  cmd->add_option("--set", request->sets, "override KEY=VALUE (scenario keys, or algo.NAME.FIELD)");
  cmd->add_option("-o,--output", request->output_dir, "output folder")->required();
  auto formats = std::make_shared<std::vector<std::string>>();
  cmd->add_option("--format", *formats,
                  "trajectory files besides TUM: kitti (<algo>.kitti + <algo>.groundtruth.kitti, matched poses)")
      ->delimiter(',');
  cmd->add_flag("--no-figures", [request](std::int64_t) { request->figures = false; }, "skip figures");
  cmd->add_flag("-q,--quiet", request->quiet, "no progress on stderr");
  cmd->add_flag("--sweep-pictures", request->pictures, "draw the sweep report's pictures (DIR/pictures/)")
      ->group("");  // for sweep workers run as --worker-exe
  cmd->add_option("--relations", request->relations_path,
                  "Kümmerle relations file of the log (t_i t_j dx dy dz roll pitch dtheta): relation_* on it");
  auto inline_modules = std::make_shared<std::vector<std::string>>();
  cmd->add_option("--exec", *inline_modules,
                  "declare an exec module NAME[:NEED,...]=COMMAND, run as --algo exec:NAME (docs/exec_protocol.md)");
  cmd->add_flag("--hide-landmark-ids", request->hide_landmark_ids,
                "strip the landmark detector's ids before the modules see the stream (they associate by themselves); "
                "association_agreement scores them against the hidden ids");
  cmd->add_flag("--skip-unavailable", request->skip_unavailable,
                "skip listed modules whose sensors the stream lacks (instead of an error)");
  cmd->callback([request, formats, inline_modules] {
    for (const auto& m : *inline_modules) DeclareExecModule(ParseInlineDeclaration(m));
    if (request->algorithms.empty()) request->algorithms = {"odometry"};
    for (const auto& f : *formats) {
      if (f == "tum") continue;
      if (f != "kitti") throw InputError("--format " + f, 0, "unknown trajectory format", "use tum or kitti");
      request->formats.push_back(TrajectoryFormat::kKitti);
    }
    const auto doc = RunAndWrite(*request);
    int bad = 0;
    for (const auto& [name, m] : doc["algorithms"].items()) {
      const std::string status = m.value("status", "?");
      if (status == "failed") ++bad;
      std::cout << name << ": " << status;
      if (m.contains("ate_rmse_m") && m["ate_rmse_m"].is_number())
        std::cout << "  ate_rmse_m=" << m["ate_rmse_m"].get<double>();
      if (m.contains("reason")) std::cout << "  (" << m["reason"].get<std::string>() << ")";
      std::cout << "\n";
    }
    std::cout << "wrote " << request->output_dir << "/metrics.json\n";
    if (bad > 0 && bad == static_cast<int>(doc["algorithms"].size())) throw CommandExit{3};
  });
}

}  // namespace slambox
