// Marginal covariances of SolvePoseGraph: a chain against the closed-form propagation,
// two parallel edges against (Omega_1 + Omega_2)^-1, and a noisy looped graph against the
// dense inverse of a finite-difference J^T J, and a looped graph with a robust kernel and an
// outlier closure against ceres::Covariance (the path SolvePoseGraph used before).
#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <memory>
#include <sstream>

#include "slam/angle_manifold.hpp"
#include "slam/pose_graph.hpp"
#include "slam/pose_graph_cost.hpp"
#include "tests/slam/pose_graph_test_support.hpp"

namespace slambox {
namespace {

Eigen::Matrix3d Info(double sigma_xy, double sigma_theta) {
  return Eigen::Vector3d(1 / (sigma_xy * sigma_xy), 1 / (sigma_xy * sigma_xy), 1 / (sigma_theta * sigma_theta)).asDiagonal();
}

PoseGraphSolveResult SolveWithMarginals(PoseGraph& g) {
  PoseGraphSolveOptions o;
  o.compute_marginals = true;
  return SolvePoseGraph(g, o);
}

TEST(PoseGraphMarginals, ChainMatchesComposedCovariances) {
  // 0 -> 1 -> 2, consistent measurements (zero residual), heading near pi so the
  // composition wraps: the marginal of pose k is the first-order propagation along the chain.
  const SE2 start(1.0, -2.0, M_PI - 0.05), d1(1.0, 0.2, 0.1), d2(0.5, -0.3, -0.4);
  const Eigen::Matrix3d O1 = Info(0.02, 0.01), O2 = Info(0.05, 0.03);
  PoseGraph g;
  g.poses = {start, start * d1, start * d1 * d2};
  g.edges = {{0, 1, d1, O1}, {1, 2, d2, O2}};
  const PoseGraphSolveResult r = SolveWithMarginals(g);
  ASSERT_EQ(r.marginal_covariances.size(), 3u);
  EXPECT_EQ(r.marginal_covariances[0], Eigen::Matrix3d::Zero());  // the anchor
  // Edge k measures T_from^-1 T_to, so the pose in the world is T_from * d with d's
  // covariance given in the from-frame.
  const Eigen::Matrix3d C1 = ComposeCovariance(start, Eigen::Matrix3d::Zero(), d1, O1.inverse());
  const Eigen::Matrix3d C2 = ComposeCovariance(start * d1, C1, d2, O2.inverse());
  EXPECT_LT((r.marginal_covariances[1] - C1).norm(), 1e-9 * C1.norm());
  EXPECT_LT((r.marginal_covariances[2] - C2).norm(), 1e-9 * C2.norm());
}

TEST(PoseGraphMarginals, ParallelEdgesAddInformation) {
  PoseGraph g;
  const SE2 d(2.0, 0.0, 0.0);
  g.poses = {SE2(), d};
  const Eigen::Matrix3d O1 = Info(0.1, 0.02), O2 = Info(0.05, 0.05);
  g.edges = {{0, 1, d, O1}, {0, 1, d, O2, true}};
  const PoseGraphSolveResult r = SolveWithMarginals(g);
  ASSERT_EQ(r.marginal_covariances.size(), 2u);
  const Eigen::Matrix3d expected = (O1 + O2).inverse();
  EXPECT_LT((r.marginal_covariances[1] - expected).norm(), 1e-9 * expected.norm());
}

TEST(PoseGraphMarginals, NoisyLoopedGraphMatchesDenseInverse) {
  testing::SyntheticGraph s = testing::MakeSquareGraph({.laps = 2, .sigma_xy_m = 0.02, .sigma_theta_rad = 0.01});
  PoseGraph g = s.graph;
  const PoseGraphSolveResult r = SolveWithMarginals(g);
  ASSERT_EQ(r.marginal_covariances.size(), g.poses.size());
  // Whitened residuals over the free poses; central differences at the solution.
  const int n = static_cast<int>(g.poses.size()), a = g.anchor;
  auto residuals = [&](const std::vector<SE2>& poses) {
    Eigen::VectorXd res(3 * g.edges.size());
    for (size_t k = 0; k < g.edges.size(); ++k) {
      const PoseGraphEdge& e = g.edges[k];
      const Eigen::Matrix3d U = e.information.llt().matrixU();
      res.segment<3>(3 * k) = U * EdgeError(poses[e.from], poses[e.to], e.T_from_to);
    }
    return res;
  };
  Eigen::MatrixXd J(3 * g.edges.size(), 3 * (n - 1));
  const double h = 1e-6;
  for (int i = 0, col = 0; i < n; ++i) {
    if (i == a) continue;
    for (int c = 0; c < 3; ++c, ++col) {
      std::vector<SE2> plus = g.poses, minus = g.poses;
      Eigen::Vector3d v = g.poses[i].vector();
      v(c) += h;
      plus[i] = SE2::FromVector(v);
      v(c) -= 2 * h;
      minus[i] = SE2::FromVector(v);
      J.col(col) = (residuals(plus) - residuals(minus)) / (2 * h);
    }
  }
  const Eigen::MatrixXd cov = (J.transpose() * J).inverse();
  for (int i = 0, col = 0; i < n; ++i) {
    if (i == a) continue;
    const Eigen::Matrix3d expected = cov.block<3, 3>(col, col);
    EXPECT_LT((r.marginal_covariances[i] - expected).norm(), 1e-5 * expected.norm()) << "pose " << i;
    col += 3;
  }
}

// ceres::Covariance (sparse QR) on the same problem at the solution: same edge costs,
// the same Cauchy loss on closures, the yaw manifold, the anchor constant.
std::vector<Eigen::Matrix3d> CeresCovariances(const PoseGraph& g, double cauchy_scale) {
  std::vector<double> x(3 * g.poses.size());
  for (size_t i = 0; i < g.poses.size(); ++i) {
    x[3 * i] = g.poses[i].x;
    x[3 * i + 1] = g.poses[i].y;
    x[3 * i + 2] = g.poses[i].theta;
  }
  ceres::Problem::Options po;
  po.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  po.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  ceres::CauchyLoss loss(cauchy_scale);
  PoseManifold manifold;
  for (const PoseGraphEdge& e : g.edges) {
    const Eigen::Matrix3d U = e.information.llt().matrixU();
    problem.AddResidualBlock(new PoseGraphEdgeCost(e.T_from_to, U), e.loop_closure ? &loss : nullptr,
                             &x[3 * static_cast<size_t>(e.from)], &x[3 * static_cast<size_t>(e.to)]);
  }
  for (size_t i = 0; i < g.poses.size(); ++i) problem.SetManifold(&x[3 * i], &manifold);
  problem.SetParameterBlockConstant(&x[3 * static_cast<size_t>(g.anchor)]);
  std::vector<std::pair<const double*, const double*>> blocks;
  for (size_t i = 0; i < g.poses.size(); ++i)
    if (static_cast<int>(i) != g.anchor) blocks.emplace_back(&x[3 * i], &x[3 * i]);
  ceres::Covariance::Options o;
  o.algorithm_type = ceres::SPARSE_QR;
  o.num_threads = 1;
  ceres::Covariance covariance(o);
  std::vector<Eigen::Matrix3d> out(g.poses.size(), Eigen::Matrix3d::Zero());
  if (!covariance.Compute(blocks, &problem)) return {};
  for (const auto& [b, same] : blocks) {
    Eigen::Matrix<double, 3, 3, Eigen::RowMajor> C;
    covariance.GetCovarianceBlock(b, b, C.data());
    out[static_cast<size_t>(b - x.data()) / 3] = C;
  }
  return out;
}

TEST(PoseGraphMarginals, RobustLoopedGraphMatchesCeresCovariance) {
  // Three noisy laps, the anchor mid-graph, one gross outlier closure that the Cauchy
  // kernel down-weights (so the loss curvature enters J^T J).
  testing::SyntheticGraph s = testing::MakeSquareGraph({.laps = 3, .sigma_xy_m = 0.03, .sigma_theta_rad = 0.01, .seed = 7});
  PoseGraph g = s.graph;
  g.anchor = 17;
  PoseGraphEdge outlier = g.edges.back();
  outlier.from = 3;
  outlier.to = 50;
  outlier.T_from_to = SE2(1.5, -2.0, 0.7);
  g.edges.push_back(outlier);
  PoseGraphSolveOptions o;
  o.compute_marginals = true;
  o.loop_kernel = RobustKernel::kCauchy;
  o.kernel_scale = 2.0;
  const PoseGraphSolveResult r = SolvePoseGraph(g, o);
  ASSERT_TRUE(r.usable);
  ASSERT_LT(r.edge_weights.back(), 0.1);  // the outlier is down-weighted
  const std::vector<Eigen::Matrix3d> expected = CeresCovariances(g, o.kernel_scale);
  ASSERT_EQ(expected.size(), g.poses.size());
  ASSERT_EQ(r.marginal_covariances.size(), g.poses.size());
  double worst = 0.0;
  for (size_t i = 0; i < g.poses.size(); ++i) {
    if (static_cast<int>(i) == g.anchor) {
      EXPECT_EQ(r.marginal_covariances[i], Eigen::Matrix3d::Zero());
      continue;
    }
    const double rel = (r.marginal_covariances[i] - expected[i]).norm() / expected[i].norm();
    worst = std::max(worst, rel);
    EXPECT_LT(rel, 1e-9) << "pose " << i;
  }
  std::ostringstream worst_text;
  worst_text << worst;
  RecordProperty("worst_relative_difference", worst_text.str());
  // Run to run: bit-identical.
  PoseGraph g2 = s.graph;
  g2.anchor = 17;
  g2.edges.push_back(outlier);
  const PoseGraphSolveResult r2 = SolvePoseGraph(g2, o);
  for (size_t i = 0; i < g.poses.size(); ++i) EXPECT_EQ(r2.marginal_covariances[i], r.marginal_covariances[i]) << i;
}

TEST(PoseGraphMarginals, RankDeficientGivesNone) {
  // Two components, one without the anchor: its poses are not determined (J^T J singular).
  PoseGraph g;
  g.poses = {SE2(), SE2(1, 0, 0), SE2(5, 0, 0), SE2(6, 0, 0)};
  g.edges = {{0, 1, SE2(1, 0, 0)}, {2, 3, SE2(1, 0, 0)}};
  PoseGraphSolveOptions o;
  o.compute_marginals = true;
  const PoseGraphSolveResult r = SolvePoseGraph(g, o);
  EXPECT_TRUE(r.marginal_covariances.empty());
}

TEST(PoseGraphMarginals, NotComputedUnlessAsked) {
  testing::SyntheticGraph s = testing::MakeSquareGraph({.laps = 1});
  EXPECT_TRUE(SolvePoseGraph(s.graph).marginal_covariances.empty());
}

}  // namespace
}  // namespace slambox
