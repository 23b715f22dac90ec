// Graduated kernel schedule: how many decades it starts above the requested scale, and that
// from a drifted odometry chain with strong outliers it closes the loops where one DCS solve
// at the final scale does not (each true closure's chi2 starts far beyond Phi).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "slam/pose_graph_graduated.hpp"
#include "slam/pose_graph_init.hpp"
#include "tests/slam/pose_graph_test_support.hpp"

namespace slambox {
namespace {

// Square laps with loop closures to lap 0, plus `outliers` random closures as confident as
// the true ones (uniform +-5 m, +-pi), fixed seed.
testing::SyntheticGraph GraphWithOutliers(int outliers, double sigma_theta_rad) {
  testing::SyntheticGraph s = testing::MakeSquareGraph(
      {.laps = 6, .poses_per_side = 10, .sigma_xy_m = 0.02, .sigma_theta_rad = sigma_theta_rad, .seed = 5});
  std::mt19937_64 rng(11);
  const int n = static_cast<int>(s.truth.size());
  std::uniform_int_distribution<int> pose(0, n - 1);
  std::uniform_real_distribution<double> xy(-5.0, 5.0), th(-M_PI, M_PI);
  const Eigen::Matrix3d information = s.graph.edges.back().information;
  for (int k = 0; k < outliers;) {
    const int i = pose(rng), j = pose(rng);
    if (std::abs(i - j) < 5) continue;
    s.graph.edges.push_back({std::min(i, j), std::max(i, j), SE2(xy(rng), xy(rng), th(rng)), information, true});
    ++k;
  }
  return s;
}

TEST(GraduatedDecades, CountsTheDecadesOfTheMedianLoopChi2AboveTheScale) {
  testing::SyntheticGraph s = testing::MakeSquareGraph({.laps = 6, .poses_per_side = 10});  // noise-free
  PoseGraphSolveOptions dcs{.loop_kernel = RobustKernel::kDcs, .kernel_scale = 1.0};
  EXPECT_EQ(GraduatedDecades(s.graph, dcs), 0);
  EXPECT_EQ(GraduatedDecades(s.graph, {.loop_kernel = RobustKernel::kNone}), 0);
  // Every pose turned by 0.1 rad more than the last: loop chi2 grows with the pose gap.
  for (size_t i = 0; i < s.graph.poses.size(); ++i) s.graph.poses[i].theta += 0.1 * static_cast<double>(i);
  const int k = GraduatedDecades(s.graph, dcs);
  std::vector<double> chi2;
  for (const PoseGraphEdge& e : s.graph.edges)
    if (e.loop_closure) {
      const Eigen::Vector3d r = EdgeError(s.graph.poses[e.from], s.graph.poses[e.to], e.T_from_to);
      chi2.push_back(r.dot(e.information * r));
    }
  std::sort(chi2.begin(), chi2.end());
  const double median = chi2[chi2.size() / 2];  // an odd count here: the middle one
  ASSERT_EQ(chi2.size() % 2, 1u);
  EXPECT_EQ(k, static_cast<int>(std::ceil(std::log10(median))));
  EXPECT_GT(k, 0);
  EXPECT_LE(k, kMaxDecades);
  dcs.kernel_scale = median / 1.01;  // just above one decade: 1
  EXPECT_EQ(GraduatedDecades(s.graph, dcs), 1);
  dcs.kernel_scale = 1.0;
  EXPECT_EQ(GraduatedDecades(s.graph, {.loop_kernel = RobustKernel::kHuber}), 0);  // convex: no schedule
  EXPECT_EQ(GraduatedDecades(s.graph, {.loop_kernel = RobustKernel::kCauchy, .kernel_scale = 1.0}), k);
  dcs.kernel_scale = 1e-12;  // a tiny scale: capped
  EXPECT_EQ(GraduatedDecades(s.graph, dcs), kMaxDecades);
}

// Odometry noise of 0.05 rad per step leaves the chained guess metres off by lap 6, so
// every true closure starts at a chi2 of 1e3-1e5 (K = 4): one DCS solve at Phi = 1 rejects
// them and ends 2.2 m off; the graduated schedule ends 0.23 m off (measured, 30 outliers;
// 0.01 rad: 0.12 / 0.14 m, both fine) with the lower robust objective, which is how
// `slambox optimize` chooses between them.
TEST(Graduated, ClosesTheLoopsFromADriftedChainDespiteOutliers) {
  testing::SyntheticGraph s = GraphWithOutliers(30, 0.05);
  s.graph.poses = SpanningTreeInitialization(s.graph);
  const PoseGraphSolveOptions dcs{.loop_kernel = RobustKernel::kDcs, .kernel_scale = 1.0};
  PoseGraph plain = s.graph, graduated = s.graph;
  const PoseGraphSolveResult p = SolvePoseGraph(plain, dcs);
  const GraduatedSolveResult g = SolvePoseGraphGraduated(graduated, dcs);
  EXPECT_EQ(g.stages, GraduatedDecades(s.graph, dcs) + 1);
  EXPECT_GE(g.stages, 3);
  EXPECT_DOUBLE_EQ(g.first_scale, std::pow(10.0, g.stages - 1));
  EXPECT_EQ(g.result.termination, "CONVERGENCE");
  EXPECT_LT(testing::MaxPositionError(graduated.poses, s.truth), 0.4);
  EXPECT_GT(testing::MaxPositionError(plain.poses, s.truth), 1.0) << "one solve closes it too now";
  EXPECT_LT(g.result.robust_chi2_final, p.robust_chi2_final);
  EXPECT_NEAR(g.result.chi2_final, Chi2(graduated), 1e-9 * g.result.chi2_final);
  // Every outlier rejected (DCS at Phi = 1 also down-weights many inliers: a 3-dof chi2
  // exceeds 1 more often than not, so only the outliers are checked).
  const size_t first_outlier = s.graph.edges.size() - 30;
  for (size_t k = first_outlier; k < s.graph.edges.size(); ++k) EXPECT_LT(g.result.edge_weights[k], 0.1) << k;
}

}  // namespace
}  // namespace slambox
