// `slambox optimize GRAPH [-o OUT.g2o] [--robust none|huber|cauchy|dcs] [--init ...] [--json]`:
// read a g2o / TORO 2D pose graph, initialize, solve with Ceres, report chi2 before/after.
// --json keeps the documented key order (DESIGN.md), then adds init, robust and counts.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "core/error.hpp"
#include "slam/g2o_io.hpp"
#include "slam/pose_graph.hpp"
#include "slam/pose_graph_init.hpp"

namespace slambox {
namespace {

struct OptimizeArgs {
  std::string graph_path;
  std::string out_path;
  std::string robust = "none";
  std::string init = "auto";
  double kernel_scale = 1.0;
  int max_iterations = 100;
  int threads = 1;
  bool json = false;
};

// Replaces the poses with the chosen initial guess; returns the method actually used.
std::string Initialize(PoseGraphFile& file, const std::string& init, const std::string& path) {
  std::string method = init;
  if (method == "auto") method = file.has_initial_guess ? "file" : "lago";
  if (method == "file" && !file.has_initial_guess)
    throw InputError(path, 0, "--init file, but the file has no VERTEX_SE2 / VERTEX2 lines (edges only)",
                     "use --init lago (or odometry) to compute an initial guess");
  if (method == "odometry") file.graph.poses = SpanningTreeInitialization(file.graph);
  if (method == "lago") file.graph.poses = LagoInitialization(file.graph);
  return method;
}

void RunOptimize(const OptimizeArgs& args) {
  PoseGraphFile file = ReadPoseGraph(args.graph_path);
  int loop_edges = 0;
  for (const PoseGraphEdge& e : file.graph.edges) loop_edges += e.loop_closure ? 1 : 0;

  const auto t0 = std::chrono::steady_clock::now();
  const std::string init = Initialize(file, args.init, args.graph_path);
  const double init_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  PoseGraphSolveOptions options;
  for (const auto& [kernel, name] : RobustKernelNames())
    if (args.robust == name) options.loop_kernel = kernel;  // --robust is checked against the same names
  options.kernel_scale = args.kernel_scale;
  options.max_iterations = args.max_iterations;
  options.num_threads = args.threads;
  // ReadPoseGraph has already rejected edges to unknown vertices and non-PD information.
  const PoseGraphSolveResult result = SolvePoseGraph(file.graph, options);
  int downweighted = 0;
  for (double w : result.edge_weights) downweighted += w < 0.5 ? 1 : 0;
  const double time_s = init_time_s + result.time_s;

  if (!args.out_path.empty() && result.usable) WritePoseGraph(args.out_path, file.graph, file.vertex_ids);

  if (args.json) {
    nlohmann::ordered_json j = {{"vertices", file.graph.poses.size()},
                        {"edges", file.graph.edges.size()},
                        {"chi2_initial", result.chi2_initial},
                        {"chi2_final", result.chi2_final},
                        {"iterations", result.iterations},
                        {"time_s", time_s},
                        {"termination", result.termination},
                        {"init", init},
                        {"init_time_s", init_time_s},
                        {"robust", args.robust},
                        {"loop_closures", loop_edges},
                        {"loop_closures_downweighted", downweighted}};
    std::cout << j.dump(2) << "\n";
  } else {
    std::printf("graph         %s\n", args.graph_path.c_str());
    std::printf("vertices      %zu\n", file.graph.poses.size());
    std::printf("edges         %zu (%d loop closures)\n", file.graph.edges.size(), loop_edges);
    std::printf("init          %s (%.3f s)\n", init.c_str(), init_time_s);
    std::printf("robust        %s", args.robust.c_str());
    if (args.robust != "none") std::printf(" (%d loop closures down-weighted below 0.5)", downweighted);
    std::printf("\nchi2_initial  %.6f\n", result.chi2_initial);
    std::printf("chi2_final    %.6f\n", result.chi2_final);
    std::printf("iterations    %d\n", result.iterations);
    std::printf("time_s        %.4f\n", time_s);
    std::printf("termination   %s\n", result.termination.c_str());
    if (!args.out_path.empty() && result.usable) std::printf("wrote         %s\n", args.out_path.c_str());
  }
  if (!result.usable) {
    std::cerr << "slambox: error: the solver failed (" << result.termination << "); no output written\n";
    throw CommandExit{1};
  }
}

}  // namespace

void AddOptimizeCommand(CLI::App& app) {
  auto args = std::make_shared<OptimizeArgs>();
  CLI::App* cmd = app.add_subcommand("optimize", "Optimize a 2D pose graph (g2o or TORO) with Ceres");
  cmd->add_option("graph", args->graph_path, "pose graph file (g2o VERTEX_SE2/EDGE_SE2 or TORO VERTEX2/EDGE2)")
      ->required();
  cmd->add_option("-o,--output", args->out_path, "write the optimized graph here (g2o)");
  cmd->add_option("--robust", args->robust, "robust kernel on loop-closure edges")
      ->check(CLI::IsMember([] {
        std::vector<std::string> names;
        for (const auto& [kernel, name] : RobustKernelNames()) names.emplace_back(name);
        return names;
      }()))
      ->capture_default_str();
  cmd->add_option("--kernel-scale", args->kernel_scale,
                  "Huber/Cauchy scale on the whitened residual; DCS's Phi (on chi2)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--init", args->init,
                  "initial guess: file (VERTEX lines), odometry (spanning tree), lago; auto = file if it has "
                  "vertices, else lago")
      ->check(CLI::IsMember({"auto", "file", "odometry", "lago"}))
      ->capture_default_str();
  cmd->add_option("--max-iterations", args->max_iterations, "Levenberg-Marquardt iteration cap")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--threads", args->threads, "Ceres threads")->check(CLI::PositiveNumber)->capture_default_str();
  cmd->add_flag("--json", args->json, "print one JSON object instead of text");
  cmd->callback([args]() { RunOptimize(*args); });
}

}  // namespace slambox
