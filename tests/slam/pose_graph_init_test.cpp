// Initial guesses: the spanning tree follows odometry; LAGO and chordal recover orientations
// (and positions) exactly without noise, across several full turns; chordal reaches the
// optimum under rotation noise that defeats LAGO's unwrapping; on a public edges-only
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

TEST(Chordal, RecoversOrientationsAndPositionsExactlyWithoutNoise) {
  testing::SyntheticGraph s = testing::MakeSquareGraph({.laps = 3, .poses_per_side = 4});
  for (SE2& p : s.graph.poses) p = SE2();  // edges only
  const SpanningTree tree = BuildSpanningTree(s.graph, false);
  const std::vector<double> theta = ChordalOrientations(s.graph, tree);
  for (size_t i = 0; i < s.truth.size(); ++i) {
    EXPECT_NEAR(NormalizeAngle(theta[i] - s.truth[i].theta), 0.0, 1e-9) << i;
    EXPECT_LE(std::abs(theta[i]), M_PI) << i;  // wrapped, not unwrapped
  }
  const std::vector<SE2> poses = ChordalInitialization(s.graph);
  EXPECT_LT(testing::MaxPositionError(poses, s.truth), 1e-9);
  s.graph.poses = poses;
  EXPECT_LT(Chi2(s.graph), 1e-15);
}

// Rotation noise of 0.3-0.5 rad per edge (honestly weighted): LAGO rounds each loop's
// 2 pi k from the tree's accumulated angle, which this much noise gets wrong, and LM from
// its guess ends in a local minimum on 4 of these 6 graphs (measured, 8 of 24 over 0.1 -
// 0.5 rad, 5 and 20 laps, seeds 1-3: never below 0.2 rad); the chordal guess reaches the
// optimum found from the truth on every one.
TEST(Chordal, ReachesTheOptimumWhereLagoUnwrapsWrongly) {
  int lago_misses = 0;
  for (double sigma_theta_rad : {0.3, 0.5})
    for (std::uint64_t seed : {1, 2, 3}) {
      const testing::SyntheticGraph s = testing::MakeSquareGraph(
          {.laps = 5, .poses_per_side = 10, .sigma_xy_m = 0.05, .sigma_theta_rad = sigma_theta_rad, .seed = seed});
      PoseGraph truth = s.graph, lago = s.graph, chordal = s.graph;
      const double chi2_opt = SolvePoseGraph(truth).chi2_final;
      lago.poses = LagoInitialization(lago);
      chordal.poses = ChordalInitialization(chordal);
      EXPECT_NEAR(SolvePoseGraph(chordal).chi2_final, chi2_opt, 1e-6 * chi2_opt) << sigma_theta_rad << " " << seed;
      lago_misses += SolvePoseGraph(lago).chi2_final > 1.01 * chi2_opt ? 1 : 0;
    }
  EXPECT_GE(lago_misses, 2) << "LAGO no longer fails here: the test does not show what chordal adds";
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
