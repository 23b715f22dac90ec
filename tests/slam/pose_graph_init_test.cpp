// Initial guesses: the spanning tree follows odometry; LAGO recovers orientations (and
// positions) exactly without noise, across several full turns; on a public edges-only
// graph where LM from the file's (identity) guess stalls, LAGO reaches the optimum.
#include <gtest/gtest.h>

#include "slam/g2o_io.hpp"
#include "slam/pose_graph.hpp"
#include "slam/pose_graph_init.hpp"
#include "tests/slam/pose_graph_test_support.hpp"

namespace slambox {
namespace {

TEST(SpanningTree, PrefersOdometryEdgesAndUnwrapsAngles) {
  const testing::SyntheticGraph s = testing::MakeSquareGraph({.laps = 3});
  const SpanningTree tree = BuildSpanningTree(s.graph);
  ASSERT_EQ(tree.order.size(), s.truth.size());
  EXPECT_EQ(tree.order.front(), s.graph.anchor);
  for (size_t v = 1; v < s.truth.size(); ++v) {
    ASSERT_GE(tree.parent_edge[v], 0);
    EXPECT_FALSE(s.graph.edges[tree.parent_edge[v]].loop_closure) << v;
  }
  // 3 laps of 4 left turns: the unwrapped heading at the end is 6 pi.
  EXPECT_NEAR(tree.theta_unwrapped.back(), 6 * M_PI, 1e-9);
  const SpanningTree shallow = BuildSpanningTree(s.graph, false);
  EXPECT_TRUE(s.graph.edges[shallow.parent_edge.back()].loop_closure);  // last pose: via its loop edge
}

TEST(SpanningTreeInitialization, NoiseFreeGraphGivesTheTruth) {
  testing::SyntheticGraph s = testing::MakeSquareGraph({.laps = 2});
  for (SE2& p : s.graph.poses) p = SE2();
  const std::vector<SE2> poses = SpanningTreeInitialization(s.graph);
  EXPECT_LT(testing::MaxPositionError(poses, s.truth), 1e-9);
}

TEST(Lago, RecoversOrientationsAndPositionsExactlyWithoutNoise) {
  testing::SyntheticGraph s = testing::MakeSquareGraph({.laps = 3, .poses_per_side = 4});
  for (SE2& p : s.graph.poses) p = SE2();  // edges only
  const SpanningTree tree = BuildSpanningTree(s.graph, false);
  const std::vector<double> theta = LagoOrientations(s.graph, tree);
  for (size_t i = 0; i < s.truth.size(); ++i)
    EXPECT_NEAR(NormalizeAngle(theta[i] - s.truth[i].theta), 0.0, 1e-9) << i;
  const std::vector<SE2> poses = LagoInitialization(s.graph);
  EXPECT_LT(testing::MaxPositionError(poses, s.truth), 1e-9);
  s.graph.poses = poses;
  EXPECT_LT(Chi2(s.graph), 1e-15);
}

TEST(Lago, NoisyGraphStartsCloseToTheOptimum) {
  testing::SyntheticGraph s = testing::MakeSquareGraph({.laps = 4, .poses_per_side = 6, .sigma_xy_m = 0.05,
                                                        .sigma_theta_rad = 0.03, .seed = 8});
  PoseGraph from_truth = s.graph;
  const double chi2_opt = SolvePoseGraph(from_truth).chi2_final;
  s.graph.poses = SpanningTreeInitialization(s.graph);
  const double chi2_odometry = Chi2(s.graph);
  s.graph.poses = LagoInitialization(s.graph);
  const double chi2_lago = Chi2(s.graph);
  EXPECT_LT(chi2_lago, 1.5 * chi2_opt);  // linear steps alone land near the optimum
  EXPECT_LT(chi2_lago, 0.1 * chi2_odometry);
  const PoseGraphSolveResult r = SolvePoseGraph(s.graph);
  EXPECT_NEAR(r.chi2_final, chi2_opt, 1e-6 * chi2_opt);
}

// CSAIL has edges only. LM from the file's guess (all poses at the origin) stalls far from
// the optimum; LAGO then LM reaches the reference optimum, as does the odometry chain here.
TEST(Lago, CsailFromEdgesOnlyReachesTheReferenceOptimum) {
  const auto refs = testing::LoadReferenceValues(SLAMBOX_SOURCE_DIR);
  const std::string path = testing::PublicDataFile(SLAMBOX_SOURCE_DIR, "posegraph/CSAIL.g2o");
  if (path.empty() || !refs.count("CSAIL.g2o"))
    GTEST_SKIP() << "posegraph/CSAIL.g2o or refs/reference_values.tsv not found; set SLAMBOX_DATA";
  const double chi2_opt = refs.at("CSAIL.g2o").chi2_opt;
  PoseGraphFile file = ReadPoseGraph(path);
  ASSERT_FALSE(file.has_initial_guess);
  PoseGraph identity = file.graph;
  const double chi2_from_identity = SolvePoseGraph(identity).chi2_final;
  file.graph.poses = LagoInitialization(file.graph);
  EXPECT_LT(Chi2(file.graph), 1.1 * chi2_opt);
  const PoseGraphSolveResult r = SolvePoseGraph(file.graph);
  EXPECT_NEAR(r.chi2_final, chi2_opt, 1e-3 * chi2_opt);
  EXPECT_GT(chi2_from_identity, 100.0 * chi2_opt);
}

}  // namespace
}  // namespace slambox
