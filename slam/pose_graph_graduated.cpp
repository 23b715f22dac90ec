#include "slam/pose_graph_graduated.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace slambox {

int GraduatedDecades(const PoseGraph& graph, const PoseGraphSolveOptions& options) {
  if (options.loop_kernel != RobustKernel::kDcs && options.loop_kernel != RobustKernel::kCauchy) return 0;
  std::vector<double> chi2;
  for (const PoseGraphEdge& edge : graph.edges) {
    if (!edge.loop_closure) continue;
    const Eigen::Vector3d e = EdgeError(graph.poses[edge.from], graph.poses[edge.to], edge.T_from_to);
    chi2.push_back(e.dot(edge.information * e));
  }
  if (chi2.empty()) return 0;
  std::nth_element(chi2.begin(), chi2.begin() + static_cast<long>(chi2.size() / 2), chi2.end());
  const double ratio = chi2[chi2.size() / 2] / options.kernel_scale;
  if (!(ratio > 1.0)) return 0;  // also NaN: a plain solve reports it
  return std::min(kMaxDecades, static_cast<int>(std::ceil(std::log10(ratio))));
}

GraduatedSolveResult SolvePoseGraphGraduated(PoseGraph& graph, const PoseGraphSolveOptions& options) {
  const int decades = GraduatedDecades(graph, options);
  GraduatedSolveResult out;
  out.stages = decades + 1;
  out.first_scale = options.kernel_scale * std::pow(10.0, decades);
  PoseGraphSolveOptions stage = options;
  double chi2_initial = 0.0, time_s = 0.0;
  int iterations = 0;
  for (int k = decades; k >= 0; --k) {
    stage.kernel_scale = options.kernel_scale * std::pow(10.0, k);
    stage.compute_marginals = options.compute_marginals && k == 0;
    stage.max_iterations = k == 0 ? options.max_iterations : std::min(options.max_iterations, kStageIterations);
    out.result = SolvePoseGraph(graph, stage);
    if (k == decades) chi2_initial = out.result.chi2_initial;
    iterations += out.result.iterations, time_s += out.result.time_s;
    if (!out.result.usable) {
      out.stages = decades - k + 1;
      break;
    }
  }
  out.result.chi2_initial = chi2_initial, out.result.iterations = iterations, out.result.time_s = time_s;
  return out;
}

}  // namespace slambox
