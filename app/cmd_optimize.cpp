// `slambox optimize GRAPH [-o OUT.g2o] [--robust none|huber|cauchy|dcs] [--init ...]
// [--groundtruth FILE]... [--json]`: read a g2o / TORO / iSAM 2D pose graph, with or without
// point landmarks, initialize, solve poses and landmarks jointly with Ceres, report chi2
// before/after and, with ground truth, ATE and landmark RMSE (app/optimize_accuracy).
// --json keeps the documented key order (DESIGN.md), then adds init, robust, counts and the
// accuracy keys (null without ground truth).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "app/commands.hpp"
#include "app/optimize_accuracy.hpp"
#include "app/optimize_init.hpp"
#include "core/error.hpp"
#include "slam/g2o_io.hpp"
#include "slam/pose_graph.hpp"

namespace slambox {
namespace {

struct OptimizeArgs {
  std::string graph_path;
  std::string out_path;
  std::string robust = "none";
  InitMethod init = InitMethod::kAuto;
  double kernel_scale = 1.0;
  int max_iterations = 100;
  int threads = 1;
  bool json = false;
  std::vector<std::string> groundtruth_paths;
  IsamNoise noise = IsamNoise::kAuto;
};

void RunOptimize(const OptimizeArgs& args) {
  PoseGraphFile file = ReadPoseGraph(args.graph_path, {.isam_noise = args.noise});
  const char* noise = file.isam_noise ? NameOf(IsamNoiseNames(), *file.isam_noise) : nullptr;
  VertexTruth truth;  // read before the solve: a bad file fails fast
  for (const std::string& path : args.groundtruth_paths) ReadVertexTruth(path, &truth);
  int loop_edges = 0;
  for (const PoseGraphEdge& e : file.graph.edges) loop_edges += e.loop_closure ? 1 : 0;

  PoseGraphSolveOptions options;
  for (const auto& [kernel, name] : RobustKernelNames())
    if (args.robust == name) options.loop_kernel = kernel;  // --robust is checked against the same names
  options.kernel_scale = args.kernel_scale;
  options.max_iterations = args.max_iterations;
  options.num_threads = args.threads;
  // ReadPoseGraph has already rejected edges to unknown vertices and non-PD information.
  const std::vector<InitAttempt> attempts = SolveWithInit(file, args.init, args.graph_path, options);
  const InitAttempt& chosen = attempts.front();
  const std::string init = InitName(chosen.init);
  const PoseGraphSolveResult& result = chosen.result;
  file.graph = chosen.graph;
  double init_time_s = 0.0, time_s = 0.0;  // every attempt counts: auto pays for all of them
  for (const InitAttempt& a : attempts) init_time_s += a.init_time_s, time_s += a.init_time_s + a.result.time_s;
  int downweighted = 0;
  for (double w : result.edge_weights) downweighted += w < 0.5 ? 1 : 0;

  if (!args.out_path.empty() && result.usable)
    WritePoseGraph(args.out_path, file.graph, file.vertex_ids, file.landmark_ids);
  // Accuracy keys through the evaluator's metric table: one definition of each key.
  Metrics accuracy;
  if (!args.groundtruth_paths.empty())
    accuracy = ScoreAgainstTruth(file, file.graph, truth, args.groundtruth_paths.front());
  const auto metric = [&](const char* key) { return MetricValue(*FindMetric(key), accuracy); };
  const size_t landmarks = file.graph.landmarks.size(), landmark_edges = file.graph.landmark_edges.size();

  if (args.json) {
    nlohmann::ordered_json j = {{"vertices", file.graph.poses.size() + landmarks},
                        {"edges", file.graph.edges.size() + landmark_edges},
                        {"chi2_initial", result.chi2_initial},
                        {"chi2_final", result.chi2_final},
                        {"iterations", result.iterations},
                        {"time_s", time_s},
                        {"termination", result.termination},
                        {"init", init},
                        {"init_requested", InitName(args.init)},
                        {"init_time_s", init_time_s},
                        {"robust", args.robust},
                        {"robust_chi2_final", result.robust_chi2_final},
                        {"robust_stages", chosen.robust_stages},
                        {"loop_closures", loop_edges},
                        {"loop_closures_downweighted", downweighted},
                        {"poses", file.graph.poses.size()},
                        {"landmarks", landmarks},
                        {"landmark_edges", landmark_edges},
                        {"ate_rmse_m", metric("ate_rmse_m")},
                        {"ate_aligned_rmse_m", metric("ate_aligned_rmse_m")},
                        {"landmark_rmse_m", metric("landmark_rmse_m")},
                        {"matched_poses", metric("matched_poses")},
                        {"landmark_matched", metric("landmark_matched")},
                        {"isam_noise", noise ? nlohmann::ordered_json(noise) : nlohmann::ordered_json()}};
    nlohmann::ordered_json tried = nlohmann::ordered_json::array();
    for (const InitAttempt& a : attempts)
      tried.push_back({{"init", InitName(a.init)},
                       {"chi2_initial", a.result.chi2_initial},
                       {"chi2_final", a.result.chi2_final},
                       {"robust_chi2_final", a.result.robust_chi2_final},
                       {"robust_stages", a.robust_stages},
                       {"iterations", a.result.iterations},
                       {"termination", a.result.termination}});
    j["init_attempts"] = tried;
    std::cout << j.dump(2) << "\n";
  } else {
    std::printf("graph         %s\n", args.graph_path.c_str());
    std::printf("vertices      %zu poses, %zu landmarks\n", file.graph.poses.size(), landmarks);
    std::printf("edges         %zu (%d loop closures), %zu landmark edges\n", file.graph.edges.size(), loop_edges,
                landmark_edges);
    if (noise) std::printf("noise         %s (the ODOMETRY / LANDMARK lines' values)\n", noise);
    std::printf("init          %s (%.3f s)\n", init.c_str(), init_time_s);
    if (attempts.size() > 1) {
      std::printf("auto tried   ");
      for (const InitAttempt& a : attempts) {
        std::printf(" %s", InitName(a.init).c_str());
        if (a.robust_stages > 1) std::printf(" (%d graduated solves)", a.robust_stages);
        if (args.robust != "none") std::printf(": objective %.6g,", a.result.robust_chi2_final);
        else std::printf(":");
        std::printf(" chi2 %.6g in %d iterations (%s);", a.result.chi2_final, a.result.iterations,
                    a.result.termination.c_str());
      }
      std::printf("\n");
    }
    std::printf("robust        %s", args.robust.c_str());
    if (args.robust != "none")
      std::printf(" (%d loop closures down-weighted below 0.5; objective %.6f; %d graduated solve%s)", downweighted,
                  result.robust_chi2_final, chosen.robust_stages, chosen.robust_stages == 1 ? "" : "s");
    std::printf("\nchi2_initial  %.6f\n", result.chi2_initial);
    std::printf("chi2_final    %.6f\n", result.chi2_final);
    std::printf("iterations    %d\n", result.iterations);
    std::printf("time_s        %.4f\n", time_s);
    std::printf("termination   %s\n", result.termination.c_str());
    if (!args.groundtruth_paths.empty()) {
      const auto number = [&](const char* key) {
        const nlohmann::json v = metric(key);
        return v.is_number() ? v.get<double>() : NAN;
      };
      std::printf("ate_rmse_m          %.6g (%lld poses matched; the graph's own gauge)\n", number("ate_rmse_m"),
                  static_cast<long long>(accuracy.matched_poses.value_or(0)));
      std::printf("ate_aligned_rmse_m  %.6g (SE(2) Umeyama)\n", number("ate_aligned_rmse_m"));
      std::printf("landmark_rmse_m     %.6g (%lld landmarks matched, same alignment)\n", number("landmark_rmse_m"),
                  static_cast<long long>(accuracy.landmark_matched.value_or(0)));
    }
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
  CLI::App* cmd =
      app.add_subcommand("optimize", "Optimize a 2D pose graph, with or without point landmarks (g2o, TORO, iSAM) with Ceres");
  cmd->add_option("graph", args->graph_path,
                  "graph file: g2o VERTEX_SE2/VERTEX_XY/EDGE_SE2/EDGE_SE2_XY/FIX, TORO VERTEX2/EDGE2, or iSAM "
                  "ODOMETRY/EDGE2/LANDMARK (square-root information; a file with any ODOMETRY or LANDMARK line has "
                  "iSAM EDGE2 lines)")
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
                  "initial guess: file (VERTEX lines), odometry (spanning tree), lago, chordal (rotations by the chordal "
                  "relaxation, then positions as lago); landmarks (all but file) at the mean of their observations from the initialized poses; auto = solve from each (file only "
                  "if every pose and landmark has a VERTEX line) and keep the lowest converged chi2")
      ->transform(CLI::CheckedTransformer(InitMethodNames(), CLI::ignore_case).description([] {
        std::string names;
        for (const auto& [name, method] : InitMethodNames()) names += (names.empty() ? "{" : ",") + name;
        return names + "}";
      }()))
      ->default_str("auto");
  cmd->add_option("--max-iterations", args->max_iterations,
                  "Levenberg-Marquardt iteration cap per solve (auto continues once an attempt that stopped at the "
                  "cap below every converged chi2)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--threads", args->threads, "Ceres threads")->check(CLI::PositiveNumber)->capture_default_str();
  cmd->add_option("--groundtruth", args->groundtruth_paths,
                  "true poses ('id x y theta') and/or landmarks ('id x y'), or g2o/TORO vertex lines, matched by "
                  "the graph's ids; may be given twice (poses, landmarks): reports ate_rmse_m, ate_aligned_rmse_m, "
                  "landmark_rmse_m")
      ->check(CLI::ExistingFile);
  cmd->add_option("--noise", args->noise,
                  "ODOMETRY / LANDMARK (and their EDGE2) values: sqrt-information (iSAM), covariance (GTSAM's "
                  "datasets), or auto: decided from the file's diagonal values (>= 1 iSAM's, <= 1 covariances)")
      ->transform(EnumTransformer(IsamNoiseNames()))
      ->default_str("auto");
  cmd->add_flag("--json", args->json, "print one JSON object instead of text");
  cmd->callback([args]() { RunOptimize(*args); });
}

}  // namespace slambox
