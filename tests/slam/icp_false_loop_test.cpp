// An injected false loop closure in a two-lap keyframe graph is switched off by the
// icp-poseslam defaults (DCS on loop edges, capped ICP information), while the true
// closures keep full weight; without a kernel the same edge wrecks the map.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "slam/edge_information.hpp"
#include "slam/icp_poseslam.hpp"
#include "slam/pose_graph.hpp"

namespace slambox {
namespace {

struct TwoLapGraph {
  PoseGraph graph;
  std::vector<SE2> truth;
  int false_edge = -1;
};

// Keyframes every 0.5 m around a 10 m x 10 m square, two laps; odometry edges with
// noise at the information caps' level; lap-2 keyframes close to lap 1.
TwoLapGraph MakeGraph(std::uint64_t seed) {
  const IcpPoseSlamConfig defaults;
  const Eigen::Matrix3d info =
      FixedInformation(defaults.info_cap_sigma_xy_m, defaults.info_cap_sigma_theta_deg * M_PI / 180);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n01(0, 1);
  TwoLapGraph g;
  SE2 pose;
  const int per_side = 20, per_lap = 4 * per_side;
  for (int i = 0; i < 2 * per_lap; ++i) {
    g.truth.push_back(pose);
    pose = pose * ((i + 1) % per_side == 0 ? SE2(0.5, 0, M_PI / 2) : SE2(0.5, 0, 0));
  }
  g.graph.poses.push_back(g.truth[0]);
  for (size_t i = 1; i < g.truth.size(); ++i) {
    const SE2 meas = Between(g.truth[i - 1], g.truth[i]) *
                     SE2(defaults.info_cap_sigma_xy_m * n01(rng), defaults.info_cap_sigma_xy_m * n01(rng),
                         defaults.info_cap_sigma_theta_deg * M_PI / 180 * n01(rng));
    g.graph.edges.push_back({static_cast<int>(i) - 1, static_cast<int>(i), meas, info, false});
    g.graph.poses.push_back(g.graph.poses.back() * meas);
  }
  for (int i = per_lap + 5; i < 2 * per_lap; i += 10)  // true closures lap 2 -> lap 1
    g.graph.edges.push_back({i - per_lap, i, Between(g.truth[i - per_lap], g.truth[i]), info, true});
  // False closure: "keyframe 150 is where keyframe 30 was" (opposite sides of the square).
  g.false_edge = static_cast<int>(g.graph.edges.size());
  g.graph.edges.push_back({30, 150, SE2(0.1, 0.0, 0.05), info, true});
  return g;
}

double MaxError(const PoseGraph& graph, const std::vector<SE2>& truth) {
  double e = 0;
  for (size_t i = 0; i < truth.size(); ++i)
    e = std::max(e, (graph.poses[i].translation() - truth[i].translation()).norm());
  return e;
}

// As icp-poseslam does: closures arrive one at a time and the graph is re-solved after each.
PoseGraphSolveResult SolveIncrementally(TwoLapGraph& g, const PoseGraphSolveOptions& options) {
  PoseGraph growing = g.graph;
  growing.edges.clear();
  PoseGraphSolveResult r;
  for (const PoseGraphEdge& e : g.graph.edges) {
    growing.edges.push_back(e);
    if (e.loop_closure) r = SolvePoseGraph(growing, options);
  }
  g.graph = growing;
  return r;
}

TEST(IcpPoseSlamBackEnd, FalseLoopClosureIsSwitchedOff) {
  const IcpPoseSlamConfig defaults;
  ASSERT_EQ(defaults.loop_kernel, RobustKernel::kDcs);
  for (std::uint64_t seed = 0; seed < 3; ++seed) {
    TwoLapGraph g = MakeGraph(seed);
    PoseGraphSolveOptions options;
    options.loop_kernel = RobustKernel::kDcs;
    options.kernel_scale = defaults.loop_kernel_scale;
    const PoseGraphSolveResult r = SolveIncrementally(g, options);
    ASSERT_TRUE(r.usable);
    EXPECT_LT(r.edge_weights[static_cast<size_t>(g.false_edge)], defaults.loop_accept_weight);
    for (size_t i = 0; i < g.graph.edges.size(); ++i) {
      if (g.graph.edges[i].loop_closure && static_cast<int>(i) != g.false_edge) {
        EXPECT_GE(r.edge_weights[i], defaults.loop_accept_weight) << "true closure " << i;
      }
    }
    TwoLapGraph reference = MakeGraph(seed);  // the same graph without the false edge, no kernel
    reference.graph.edges.pop_back();
    SolveIncrementally(reference, {});
    EXPECT_LT(MaxError(g.graph, g.truth), MaxError(reference.graph, reference.truth) + 0.01);

    TwoLapGraph plain = MakeGraph(seed);
    SolveIncrementally(plain, {});  // no kernel: the false edge drags the map
    EXPECT_GT(MaxError(plain.graph, plain.truth), 1.0);
    std::printf("seed %d: false-edge weight %.2e, max error %.3f m (dcs) vs %.3f m (none)\n", static_cast<int>(seed),
                r.edge_weights[static_cast<size_t>(g.false_edge)], MaxError(g.graph, g.truth),
                MaxError(plain.graph, plain.truth));
  }
}

}  // namespace
}  // namespace slambox
