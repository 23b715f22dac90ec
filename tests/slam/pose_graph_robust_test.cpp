// Robust kernels on loop closures: a false loop closure (two distant places claimed to
// coincide) distorts the plain solution; DCS and Cauchy give it a weight near zero and
// keep the trajectory, while true loop closures keep weights near one.
#include <gtest/gtest.h>

#include <cstdio>

#include "slam/pose_graph.hpp"
#include "slam/pose_graph_init.hpp"
#include "tests/slam/pose_graph_test_support.hpp"

namespace slambox {
namespace {

struct FalseLoopCase {
  testing::SyntheticGraph s;
  size_t false_edge = 0;
};

FalseLoopCase MakeFalseLoopCase() {
  FalseLoopCase c;
  c.s = testing::MakeSquareGraph({.laps = 2, .poses_per_side = 5, .sigma_xy_m = 0.02,
                                  .sigma_theta_rad = 0.01, .seed = 21});
  // Pose 2 (bottom side) and pose 12 (top side) are 4 m apart; claim they coincide,
  // with the same confidence as a true loop closure.
  const Eigen::Matrix3d information = c.s.graph.edges.back().information;
  c.false_edge = c.s.graph.edges.size();
  c.s.graph.edges.push_back({2, 12, SE2(0.0, 0.0, 0.0), information, true});
  c.s.graph.poses = SpanningTreeInitialization(c.s.graph);  // odometry: the tree avoids the loop edges
  return c;
}

// Scales for a 3-dof chi2 of true edges (mean 3): DCS's Phi on chi2, Cauchy's on |r|.
double ScaleFor(RobustKernel kernel) { return kernel == RobustKernel::kDcs ? 10.0 : 3.0; }

double SolveAndMeasure(RobustKernel kernel, PoseGraphSolveResult* result, bool with_false_edge = true) {
  FalseLoopCase c = MakeFalseLoopCase();
  if (!with_false_edge) c.s.graph.edges.pop_back();
  *result = SolvePoseGraph(c.s.graph, {.loop_kernel = kernel, .kernel_scale = ScaleFor(kernel)});
  return testing::MaxPositionError(c.s.graph.poses, c.s.truth);
}

double MeanTrueLoopWeight(const PoseGraphSolveResult& r, const FalseLoopCase& c) {
  double sum = 0.0;
  int count = 0;
  for (size_t k = 0; k < c.s.graph.edges.size(); ++k)
    if (c.s.graph.edges[k].loop_closure && k != c.false_edge) sum += r.edge_weights[k], ++count;
  return sum / count;
}

TEST(RobustKernels, WithoutKernelAFalseLoopClosureDistortsTheMap) {
  PoseGraphSolveResult r;
  const double error_m = SolveAndMeasure(RobustKernel::kNone, &r);
  EXPECT_GT(error_m, 0.5);
  for (double w : r.edge_weights) EXPECT_EQ(w, 1.0);
}

TEST(RobustKernels, DcsAndCauchyDownWeightTheFalseLoopClosure) {
  const FalseLoopCase c = MakeFalseLoopCase();
  for (RobustKernel kernel : {RobustKernel::kDcs, RobustKernel::kCauchy}) {
    PoseGraphSolveResult r;
    const double error_m = SolveAndMeasure(kernel, &r);
    SCOPED_TRACE(kernel == RobustKernel::kDcs ? "DCS" : "Cauchy");
    EXPECT_TRUE(r.usable);
    EXPECT_LT(r.edge_weights[c.false_edge], 1e-3);
    EXPECT_GT(MeanTrueLoopWeight(r, c), 0.8);
    PoseGraphSolveResult clean;
    const double clean_error_m = SolveAndMeasure(RobustKernel::kNone, &clean, false);
    std::printf("max position error: clean graph %.4f m, robust with false edge %.4f m\n", clean_error_m, error_m);
    EXPECT_LT(error_m, clean_error_m + 0.01);
    // Odometry edges are never robustified.
    for (size_t k = 0; k < c.s.graph.edges.size(); ++k)
      if (!c.s.graph.edges[k].loop_closure) {
        EXPECT_EQ(r.edge_weights[k], 1.0);
      }
    // chi2 is reported without the kernel: it includes the false edge's full error.
    EXPECT_GT(r.chi2_final, 4.0 * 4.0 * c.s.graph.edges[c.false_edge].information(0, 0) * 0.5);
  }
}

TEST(RobustKernels, HuberLimitsButDoesNotRemoveTheFalseLoopClosure) {
  PoseGraphSolveResult none, huber;
  const double error_none = SolveAndMeasure(RobustKernel::kNone, &none);
  const double error_huber = SolveAndMeasure(RobustKernel::kHuber, &huber);
  const FalseLoopCase c = MakeFalseLoopCase();
  EXPECT_LT(error_huber, error_none);
  EXPECT_LT(huber.edge_weights[c.false_edge], 0.1);
}

}  // namespace
}  // namespace slambox
