// SolvePoseGraph: exact recovery of a noise-free graph, agreement with a brute-force
// dense Gauss-Newton on a noisy one, the anchor, input errors, and intel's optimum.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "core/error.hpp"
#include "slam/g2o_io.hpp"
#include "slam/pose_graph.hpp"
#include "tests/slam/pose_graph_test_support.hpp"

namespace slambox {
namespace {

using testing::MakeSquareGraph;
using testing::Perturbed;

TEST(SolvePoseGraph, RecoversNoiseFreeGraphExactlyFromPerturbedGuess) {
  testing::SyntheticGraph s = MakeSquareGraph({.laps = 3});
  s.graph.poses = Perturbed(s.truth, s.graph.anchor, 0.3, 0.2, 11);
  ASSERT_GT(Chi2(s.graph), 100.0);
  const PoseGraphSolveResult r = SolvePoseGraph(s.graph);
  EXPECT_TRUE(r.usable);
  EXPECT_EQ(r.termination, "CONVERGENCE");
  EXPECT_GT(r.chi2_initial, 100.0);
  EXPECT_LT(r.chi2_final, 1e-12);
  EXPECT_LT(testing::MaxPositionError(s.graph.poses, s.truth), 1e-6);
  for (size_t i = 0; i < s.truth.size(); ++i)
    EXPECT_NEAR(NormalizeAngle(s.graph.poses[i].theta - s.truth[i].theta), 0.0, 1e-7) << i;
}

// Dense Gauss-Newton with finite-difference Jacobians over all poses but the anchor:
// slow and simple, an independent check of the optimum.
double BruteForceOptimum(PoseGraph g) {
  const int n = static_cast<int>(g.poses.size());
  auto residuals = [&](const std::vector<SE2>& poses) {
    Eigen::VectorXd r(3 * g.edges.size());
    for (size_t k = 0; k < g.edges.size(); ++k) {
      const PoseGraphEdge& e = g.edges[k];
      const Eigen::Matrix3d U = e.information.llt().matrixU();
      r.segment<3>(3 * k) = U * EdgeError(poses[e.from], poses[e.to], e.T_from_to);
    }
    return r;
  };
  for (int iter = 0; iter < 30; ++iter) {
    const Eigen::VectorXd r0 = residuals(g.poses);
    Eigen::MatrixXd J(r0.size(), 3 * n);
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) {
        std::vector<SE2> plus = g.poses, minus = g.poses;
        Eigen::Vector3d d = Eigen::Vector3d::Zero();
        d(c) = 1e-6;
        plus[i] = SE2::FromVector(g.poses[i].vector() + d);
        minus[i] = SE2::FromVector(g.poses[i].vector() - d);
        J.col(3 * i + c) = (residuals(plus) - residuals(minus)) / 2e-6;
      }
    J.middleCols<3>(3 * g.anchor).setZero();
    Eigen::MatrixXd H = J.transpose() * J;
    H.block<3, 3>(3 * g.anchor, 3 * g.anchor) = Eigen::Matrix3d::Identity();
    const Eigen::VectorXd dx = H.ldlt().solve(-J.transpose() * r0);
    for (int i = 0; i < n; ++i) g.poses[i] = SE2::FromVector(g.poses[i].vector() + dx.segment<3>(3 * i));
    if (dx.norm() < 1e-12) break;
  }
  return Chi2(g);
}

TEST(SolvePoseGraph, NoisyGraphReachesBruteForceOptimum) {
  testing::SyntheticGraph s = MakeSquareGraph({.laps = 2, .poses_per_side = 3, .sigma_xy_m = 0.05,
                                               .sigma_theta_rad = 0.02, .seed = 3});
  const double chi2_brute = BruteForceOptimum(s.graph);  // started from the truth
  s.graph.poses = Perturbed(s.truth, s.graph.anchor, 0.2, 0.1, 5);
  const PoseGraphSolveResult r = SolvePoseGraph(s.graph);
  EXPECT_GT(chi2_brute, 1.0);  // noisy: the optimum is not zero
  EXPECT_NEAR(r.chi2_final, chi2_brute, 1e-6 * chi2_brute);
}

TEST(SolvePoseGraph, IsDeterministic) {
  testing::SyntheticGraph s = MakeSquareGraph({.laps = 2, .sigma_xy_m = 0.05, .sigma_theta_rad = 0.02, .seed = 6});
  s.graph.poses = Perturbed(s.truth, s.graph.anchor, 0.2, 0.1, 7);
  PoseGraph a = s.graph, b = s.graph;
  const PoseGraphSolveResult ra = SolvePoseGraph(a, {.loop_kernel = RobustKernel::kDcs});
  const PoseGraphSolveResult rb = SolvePoseGraph(b, {.loop_kernel = RobustKernel::kDcs});
  EXPECT_EQ(ra.chi2_final, rb.chi2_final);
  EXPECT_EQ(ra.iterations, rb.iterations);
  EXPECT_EQ(ra.edge_weights, rb.edge_weights);
  for (size_t i = 0; i < a.poses.size(); ++i) {
    EXPECT_EQ(a.poses[i].x, b.poses[i].x);
    EXPECT_EQ(a.poses[i].y, b.poses[i].y);
    EXPECT_EQ(a.poses[i].theta, b.poses[i].theta);
  }
}

TEST(SolvePoseGraph, HoldsTheAnchorFixed) {
  testing::SyntheticGraph s = MakeSquareGraph({.laps = 1});
  s.graph.anchor = 7;
  const SE2 anchor_pose(10.0, -3.0, 1.0);  // the whole solution is expressed in this gauge
  s.graph.poses = Perturbed(s.truth, -1, 0.1, 0.05, 2);
  s.graph.poses[7] = anchor_pose;
  SolvePoseGraph(s.graph);
  EXPECT_EQ(s.graph.poses[7].x, anchor_pose.x);
  EXPECT_EQ(s.graph.poses[7].y, anchor_pose.y);
  EXPECT_EQ(s.graph.poses[7].theta, anchor_pose.theta);
  // Relative poses are the truth's.
  const SE2 T = Between(s.graph.poses[7], s.graph.poses[12]), T_true = Between(s.truth[7], s.truth[12]);
  EXPECT_NEAR((T.translation() - T_true.translation()).norm(), 0.0, 1e-6);
}

TEST(SolvePoseGraph, RejectsEdgesToMissingPosesAndNonPositiveDefiniteInformation) {
  testing::SyntheticGraph s = MakeSquareGraph({.laps = 1});
  PoseGraph missing = s.graph;
  missing.edges.push_back({0, static_cast<int>(missing.poses.size()), SE2(), Eigen::Matrix3d::Identity(), true});
  EXPECT_THROW(SolvePoseGraph(missing), InputError);
  PoseGraph negative = s.graph;
  negative.edges[3].information(2, 2) = -1.0;
  try {
    SolvePoseGraph(negative);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("edge 3"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("positive definite"), std::string::npos) << e.what();
  }
  PoseGraph bad_anchor = s.graph;
  bad_anchor.anchor = -1;
  EXPECT_THROW(SolvePoseGraph(bad_anchor), InputError);
  PoseGraph nan_pose = s.graph;
  nan_pose.poses[4].x = NAN;
  EXPECT_THROW(SolvePoseGraph(nan_pose), InputError);
}

TEST(SolvePoseGraph, IntelReachesReferenceOptimum) {
  const auto refs = testing::LoadReferenceValues(SLAMBOX_SOURCE_DIR);
  const std::string path = testing::PublicDataFile(SLAMBOX_SOURCE_DIR, "posegraph/intel.g2o");
  if (path.empty() || !refs.count("intel.g2o"))
    GTEST_SKIP() << "posegraph/intel.g2o or refs/reference_values.tsv not found; set SLAMBOX_DATA";
  PoseGraphFile file = ReadPoseGraph(path);
  const PoseGraphSolveResult r = SolvePoseGraph(file.graph);
  const double chi2_opt = refs.at("intel.g2o").chi2_opt;
  EXPECT_NEAR(r.chi2_initial, refs.at("intel.g2o").chi2_init, 1e-9 * r.chi2_initial);
  EXPECT_NEAR(r.chi2_final, chi2_opt, 1e-3 * chi2_opt);
  EXPECT_EQ(r.termination, "CONVERGENCE");
}

}  // namespace
}  // namespace slambox
