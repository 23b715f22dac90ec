// `--init auto`'s machinery: an attempt the iteration cap stopped below every converged
// chi2 is solved once more from where it stopped (and nothing else is); a guess equal to an
// earlier one is not solved again; a non-convex kernel adds a graduated attempt from the chain.
#include <gtest/gtest.h>

#include "app/optimize_init.hpp"
#include "slam/pose_graph_init.hpp"
#include "tests/slam/pose_graph_test_support.hpp"

namespace slambox {
namespace {

// 0.5 rad of rotation noise per edge: from LAGO's guess LM converges to a local minimum
// (chi2 889.5 in 30 iterations), from the chordal guess to the optimum (523.51 in 13).
PoseGraphFile NoisyFile() {
  PoseGraphFile file;
  file.graph = testing::MakeSquareGraph(
                   {.laps = 5, .poses_per_side = 10, .sigma_xy_m = 0.05, .sigma_theta_rad = 0.5, .seed = 2})
                   .graph;
  return file;
}

TEST(OptimizeInit, ContinuesTheStalledAttemptBelowTheConvergedOne) {
  const PoseGraphFile file = NoisyFile();
  std::vector<InitAttempt> attempts = {SolveFrom(file, InitMethod::kLago, {}).front(),
                                       SolveFrom(file, InitMethod::kChordal, {.max_iterations = 5}).front()};
  ASSERT_EQ(attempts[0].result.termination, "CONVERGENCE");
  ASSERT_EQ(attempts[1].result.termination, "NO_CONVERGENCE");
  ASSERT_LT(attempts[1].result.chi2_final, attempts[0].result.chi2_final);
  const PoseGraphSolveResult lago = attempts[0].result, stalled = attempts[1].result;
  ContinueTheLowestStalled(attempts, {.max_iterations = 50});
  EXPECT_EQ(attempts[0].result.iterations, lago.iterations);  // untouched
  EXPECT_EQ(attempts[1].result.termination, "CONVERGENCE");
  EXPECT_GT(attempts[1].result.iterations, stalled.iterations);
  EXPECT_EQ(attempts[1].result.chi2_initial, stalled.chi2_initial);  // of the guess, not of the restart
  EXPECT_LT(attempts[1].result.chi2_final, stalled.chi2_final);
  EXPECT_NEAR(attempts[1].result.chi2_final, Chi2(attempts[1].graph), 1e-9 * attempts[1].result.chi2_final);
}

TEST(OptimizeInit, ContinuesNothingWhenNoneConvergedOrTheStalledIsHigher) {
  const PoseGraphFile file = NoisyFile();
  std::vector<InitAttempt> none = {SolveFrom(file, InitMethod::kLago, {.max_iterations = 3}).front(),
                                   SolveFrom(file, InitMethod::kChordal, {.max_iterations = 3}).front()};
  const int before = none[1].result.iterations;
  ContinueTheLowestStalled(none, {.max_iterations = 3});
  EXPECT_EQ(none[1].result.iterations, before);
  std::vector<InitAttempt> higher = {SolveFrom(file, InitMethod::kChordal, {}).front(),
                                     SolveFrom(file, InitMethod::kLago, {.max_iterations = 3}).front()};
  ASSERT_EQ(higher[0].result.termination, "CONVERGENCE");
  ContinueTheLowestStalled(higher, {});
  EXPECT_EQ(higher[1].result.iterations, 3);
}

TEST(OptimizeInit, AutoChoosesTheLowestAndListsEveryAttempt) {
  const PoseGraphFile file = NoisyFile();  // no VERTEX guess: lago, chordal, odometry
  const std::vector<InitAttempt> attempts = SolveWithInit(file, InitMethod::kAuto, "noisy.g2o", {});
  ASSERT_EQ(attempts.size(), 3u);
  EXPECT_EQ(attempts.front().init, InitMethod::kChordal);
  for (const InitAttempt& a : attempts) EXPECT_GE(a.result.chi2_final, attempts.front().result.chi2_final * (1 - 1e-6));
  EXPECT_EQ(InitName(InitMethod::kChordal), "chordal");
  EXPECT_EQ(InitMethodNames().at("chordal"), InitMethod::kChordal);
}

TEST(OptimizeInit, AGuessEqualToAnEarlierOneIsNotSolvedAgain) {
  PoseGraphFile file = NoisyFile();
  file.graph.poses = SpanningTreeInitialization(file.graph);  // VERTEX lines = the odometry chain
  for (size_t i = 1; i < file.graph.poses.size(); ++i) {  // as printed to 6 decimals; the anchor as is
    const SE2& p = file.graph.poses[i];
    file.graph.poses[i] = SE2(p.x + 4e-7, p.y - 4e-7, p.theta + 4e-7);
  }
  file.has_initial_guess = true;
  const std::vector<InitAttempt> attempts = SolveWithInit(file, InitMethod::kAuto, "chain.g2o", {});
  int file_attempts = 0;
  for (const InitAttempt& a : attempts) {
    EXPECT_NE(a.init, InitMethod::kOdometry);
    file_attempts += a.init == InitMethod::kFile ? 1 : 0;
  }
  EXPECT_EQ(file_attempts, 1);
  EXPECT_EQ(attempts.size(), 3u);  // file, lago, chordal
  EXPECT_EQ(SolveWithInit(file, InitMethod::kOdometry, "chain.g2o", {}).size(), 1u);  // asked for: solved
}

// With DCS the odometry chain (and only it, of the guesses made from edges) is also solved
// through the graduated schedule; the attempts say how many solves each took.
TEST(OptimizeInit, DcsAddsAGraduatedAttemptFromTheChainOnly) {
  const PoseGraphFile file = NoisyFile();
  const PoseGraphSolveOptions dcs{.loop_kernel = RobustKernel::kDcs, .kernel_scale = 1.0};
  const std::vector<InitAttempt> chain = SolveFrom(file, InitMethod::kOdometry, dcs);
  ASSERT_EQ(chain.size(), 2u);
  EXPECT_EQ(chain[0].robust_stages, 1);
  EXPECT_GT(chain[1].robust_stages, 1);
  EXPECT_EQ(SolveFrom(file, InitMethod::kLago, dcs).size(), 1u);
  EXPECT_EQ(SolveFrom(file, InitMethod::kOdometry, {}).size(), 1u);  // no kernel: one solve
  const std::vector<InitAttempt> attempts = SolveWithInit(file, InitMethod::kAuto, "noisy.g2o", dcs);
  for (const InitAttempt& a : attempts)
    EXPECT_GE(a.result.robust_chi2_final, attempts.front().result.robust_chi2_final * (1 - 1e-6));
}

}  // namespace
}  // namespace slambox
