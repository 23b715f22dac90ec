// Pose graph solve times on the public 2D graphs (skipped when absent), side by side with
// a plain Ceres LM solve laid out as Ceres' examples/slam/pose_graph_2d (autodiff cost,
// separate x, y, yaw blocks, yaw on an angle manifold, sparse normal Cholesky, 1 thread)
// from the same start, so both are timed under the same machine load.
//   ./build/bench/pose_graph_bench [--benchmark_filter=intel]
// Counters: chi2_init / chi2_final (g2o convention, no kernel), iterations.
// <graph>/<start>/slambox_marginals: the same solve plus every pose's marginal covariance
// (compute_marginals), so its time minus slambox's is the cost of the marginals.
#include <benchmark/benchmark.h>
#include <ceres/ceres.h>

#include <cstdio>
#include <filesystem>
#include <memory>

#include "slam/g2o_io.hpp"
#include "slam/pose_graph.hpp"
#include "slam/angle_manifold.hpp"
#include "slam/dcs_loss.hpp"
#include "slam/pose_graph_cost.hpp"
#include "slam/pose_graph_init.hpp"
#include "tests/support/public_data.hpp"

namespace slambox {
namespace {

// The Ceres example's edge term: residual U [R_a^T (p_b - p_a) - p_ab; wrap(yaw_b - yaw_a - yaw_ab)].
struct ExampleEdgeTerm {
  ExampleEdgeTerm(const SE2& T_ab, const Eigen::Matrix3d& U) : T_ab(T_ab), U(U) {}
  template <typename T>
  bool operator()(const T* x_a, const T* y_a, const T* yaw_a, const T* x_b, const T* y_b, const T* yaw_b,
                  T* residuals) const {
    using std::cos, std::sin;
    const T dx = *x_b - *x_a, dy = *y_b - *y_a;
    const T c = cos(*yaw_a), s = sin(*yaw_a);
    T e[3] = {c * dx + s * dy - T(T_ab.x), -s * dx + c * dy - T(T_ab.y), *yaw_b - *yaw_a - T(T_ab.theta)};
    e[2] += NormalizeAngle(ScalarPart(e[2])) - ScalarPart(e[2]);
    for (int r = 0; r < 3; ++r) residuals[r] = T(U(r, 0)) * e[0] + T(U(r, 1)) * e[1] + T(U(r, 2)) * e[2];
    return true;
  }
  SE2 T_ab;
  Eigen::Matrix3d U;
};

PoseGraphSolveResult SolveCeresExampleLayout(PoseGraph& graph) {
  const size_t n = graph.poses.size();
  std::vector<double> x(n), y(n), yaw(n);
  for (size_t i = 0; i < n; ++i) x[i] = graph.poses[i].x, y[i] = graph.poses[i].y, yaw[i] = graph.poses[i].theta;
  PoseGraphSolveResult result;
  result.chi2_initial = Chi2(graph);
  ceres::Problem problem;
  ceres::Manifold* angle = MakeAngleManifold();  // owned by the problem
  for (const PoseGraphEdge& e : graph.edges) {
    Eigen::Matrix3d U;
    SqrtInformation(e.information, &U);
    const int a = e.from, b = e.to;
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<ExampleEdgeTerm, 3, 1, 1, 1, 1, 1, 1>(new ExampleEdgeTerm(e.T_from_to, U)),
        nullptr, &x[a], &y[a], &yaw[a], &x[b], &y[b], &yaw[b]);
    problem.SetManifold(&yaw[a], angle);
    problem.SetManifold(&yaw[b], angle);
  }
  problem.SetParameterBlockConstant(&x[graph.anchor]);
  problem.SetParameterBlockConstant(&y[graph.anchor]);
  problem.SetParameterBlockConstant(&yaw[graph.anchor]);
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.max_num_iterations = 100;
  options.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  for (size_t i = 0; i < n; ++i) graph.poses[i] = SE2(x[i], y[i], yaw[i]);
  result.chi2_final = Chi2(graph);
  result.iterations = static_cast<int>(summary.iterations.size()) - 1;
  result.termination = ceres::TerminationTypeToString(summary.termination_type);
  return result;
}

enum class Method { kCeresExample, kSlambox, kSlamboxMarginals };
enum class Start { kFile, kOdometry, kLago, kChordal };

void BM_PoseGraph(benchmark::State& state, const PoseGraphFile* file, Method method, Start start) {
  PoseGraphSolveResult r;
  for (auto _ : state) {
    PoseGraph graph = file->graph;
    if (start == Start::kOdometry) graph.poses = SpanningTreeInitialization(graph);
    if (start == Start::kLago) graph.poses = LagoInitialization(graph);
    if (start == Start::kChordal) graph.poses = ChordalInitialization(graph);
    PoseGraphSolveOptions options;
    options.compute_marginals = method == Method::kSlamboxMarginals;
    r = method == Method::kCeresExample ? SolveCeresExampleLayout(graph) : SolvePoseGraph(graph, options);
    benchmark::DoNotOptimize(graph.poses.data());
  }
  state.counters["chi2_init"] = r.chi2_initial;
  state.counters["chi2_final"] = r.chi2_final;
  state.counters["iterations"] = r.iterations;
  if (method == Method::kSlamboxMarginals) state.counters["marginals"] = static_cast<double>(r.marginal_covariances.size());
  state.SetLabel(r.termination);
}

}  // namespace
}  // namespace slambox

int main(int argc, char** argv) {
  using namespace slambox;
  const std::string source_dir = std::filesystem::path(__FILE__).parent_path().parent_path().string();
  // name, file, repetitions (each repetition is one solve)
  const std::vector<std::tuple<std::string, std::string, int>> graphs = {
      {"intel", "posegraph/intel.g2o", 10},         {"CSAIL", "posegraph/CSAIL.g2o", 10},
      {"manhattan", "posegraph/manhattan.g2o", 3}, {"city10000", "posegraph/city10000.g2o", 3},
      {"w10000", "posegraph/w10000_toro.graph", 1}};
  static std::vector<std::unique_ptr<PoseGraphFile>> files;
  for (const auto& [name, relative, reps] : graphs) {
    const std::string path = testing::PublicDataFile(source_dir, relative);
    if (path.empty()) {
      std::fprintf(stderr, "skipping %s: %s not found (set SLAMBOX_DATA)\n", name.c_str(), relative.c_str());
      continue;
    }
    files.push_back(std::make_unique<PoseGraphFile>(ReadPoseGraph(path)));
    const PoseGraphFile* f = files.back().get();
    const std::vector<std::pair<std::string, Start>> starts =
        f->has_initial_guess ? std::vector<std::pair<std::string, Start>>{{"file", Start::kFile},
                                                                          {"odometry", Start::kOdometry},
                                                                          {"lago", Start::kLago},
                                                                          {"chordal", Start::kChordal}}
                             : std::vector<std::pair<std::string, Start>>{{"odometry", Start::kOdometry},
                                                                          {"lago", Start::kLago},
                                                                          {"chordal", Start::kChordal}};
    for (const auto& [start_name, start] : starts) {
      for (const auto& [method_name, method] :
           {std::pair<std::string, Method>{"ceres_example", Method::kCeresExample}, {"slambox", Method::kSlambox},
            {"slambox_marginals", Method::kSlamboxMarginals}}) {
        if (method == Method::kCeresExample && (start == Start::kLago || start == Start::kChordal)) continue;  // the baseline: plain LM
        if (method == Method::kSlamboxMarginals && start != starts.front().second) continue;  // one start suffices
        benchmark::RegisterBenchmark((name + "/" + start_name + "/" + method_name).c_str(), BM_PoseGraph, f,
                                     method, start)
            ->Unit(benchmark::kMillisecond)
            ->Iterations(1)
            ->Repetitions(reps)
            ->ReportAggregatesOnly(reps > 1);
      }
    }
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
