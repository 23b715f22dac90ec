// The pose graph's error function: EdgeError / Chi2 against hand-computed values and the
// public reference values, the Ceres cost's Jacobians against finite differences, the
// angle manifold's wrap and the DCS loss.
#include <gtest/gtest.h>

#include <memory>
#include <random>

#include "slam/g2o_io.hpp"
#include "slam/pose_graph.hpp"
#include "slam/angle_manifold.hpp"
#include "slam/dcs_loss.hpp"
#include "slam/pose_graph_cost.hpp"
#include "slam/pose_graph_init.hpp"
#include "tests/slam/pose_graph_test_support.hpp"

namespace slambox {
namespace {

TEST(EdgeError, HandComputed) {
  // T_i at (1, 2) facing +y; T_j at (1, 5) facing -x: j is 3 m ahead of i, turned +90 deg.
  const SE2 T_i(1.0, 2.0, M_PI / 2), T_j(1.0, 5.0, M_PI);
  const Eigen::Vector3d e = EdgeError(T_i, T_j, SE2(2.5, 0.5, 0.25));
  EXPECT_NEAR(e.x(), 3.0 - 2.5, 1e-12);
  EXPECT_NEAR(e.y(), 0.0 - 0.5, 1e-12);
  EXPECT_NEAR(e.z(), M_PI / 2 - 0.25, 1e-12);
  EXPECT_NEAR(EdgeError(T_i, T_j, Between(T_i, T_j)).norm(), 0.0, 1e-12);
}

TEST(EdgeError, AngleWrapsAtPlusMinusPi) {
  // theta_j - theta_i - theta_ij = 2 pi - 0.2 is really -0.2; -(2 pi - 0.2) is 0.2.
  const SE2 origin;
  EXPECT_NEAR(EdgeError(SE2(0, 0, -M_PI + 0.1), SE2(0, 0, M_PI - 0.1), SE2(0, 0, 0)).z(), -0.2, 1e-12);
  EXPECT_NEAR(EdgeError(SE2(0, 0, M_PI - 0.1), SE2(0, 0, -M_PI + 0.1), SE2(0, 0, 0)).z(), 0.2, 1e-12);
  EXPECT_NEAR(EdgeError(origin, SE2(0, 0, M_PI - 0.05), SE2(0, 0, -M_PI + 0.05)).z(), -0.1, 1e-12);
  for (double d : {-3.0, -1.0, 0.0, 1.0, 3.0}) {
    const double ez = EdgeError(SE2(0, 0, 3.0), SE2(0, 0, 3.0 + d), SE2(0, 0, 0)).z();
    EXPECT_NEAR(ez, d, 1e-12);
    EXPECT_GE(ez, -M_PI);
    EXPECT_LT(ez, M_PI);
  }
}

TEST(Chi2, HandComputedWithFullInformation) {
  PoseGraph g;
  g.poses = {SE2(0, 0, 0), SE2(1.0, 0.5, 0.1)};
  Eigen::Matrix3d I;
  I << 4, 1, 0.5, 1, 9, 0.2, 0.5, 0.2, 16;
  g.edges.push_back({0, 1, SE2(0.9, 0.3, 0.0), I, false});
  // e = (0.1, 0.2, 0.1): e^T I e = 4(.01) + 9(.04) + 16(.01) + 2[1(.02) + 0.5(.01) + 0.2(.02)]
  EXPECT_NEAR(Chi2(g), 0.04 + 0.36 + 0.16 + 2 * (0.02 + 0.005 + 0.004), 1e-12);
}

TEST(PoseGraphEdgeCost, ResidualIsWhitenedErrorAndJacobiansMatchFiniteDifferences) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  Eigen::Matrix3d I;
  I << 50, 5, 2, 5, 80, -3, 2, -3, 200;
  Eigen::Matrix3d U;
  ASSERT_TRUE(SqrtInformation(I, &U));
  EXPECT_TRUE((U.transpose() * U).isApprox(I, 1e-12));
  int checked = 0;
  for (int trial = 0; trial < 30; ++trial) {
    const SE2 T_ij(u(rng), u(rng), u(rng));
    double p[6] = {u(rng), u(rng), u(rng), u(rng), u(rng), u(rng)};  // pose i, pose j
    const SE2 T_i(p[0], p[1], p[2]), T_j(p[3], p[4], p[5]);
    // Stay away from the +-pi seam of the wrapped angle, where differences jump.
    if (std::abs(EdgeError(T_i, T_j, T_ij).z()) > 3.0) continue;
    ++checked;
    const PoseGraphEdgeCost cost(T_ij, U);
    double* params[2] = {&p[0], &p[3]};  // (x, y, theta) of pose i and pose j
    double r[3], J0[9], J1[9];
    double* jac[2] = {J0, J1};
    ASSERT_TRUE(cost.Evaluate(params, r, jac));
    const Eigen::Vector3d e = EdgeError(T_i, T_j, T_ij);
    EXPECT_NEAR(Eigen::Vector3d(r[0], r[1], r[2]).squaredNorm(), e.dot(I * e), 1e-9);
    for (int b = 0; b < 2; ++b) {
      for (int c = 0; c < 3; ++c) {
        const double h = 1e-6, saved = params[b][c];
        double rp[3], rm[3];
        params[b][c] = saved + h;
        cost.Evaluate(params, rp, nullptr);
        params[b][c] = saved - h;
        cost.Evaluate(params, rm, nullptr);
        params[b][c] = saved;
        for (int row = 0; row < 3; ++row)  // Ceres Jacobians are row-major
          EXPECT_NEAR(jac[b][row * 3 + c], (rp[row] - rm[row]) / (2 * h), 1e-5)
              << "block " << b << " column " << c << " row " << row;
      }
    }
  }
  EXPECT_GE(checked, 15);
}

TEST(SqrtInformation, RejectsNonPositiveDefinite) {
  Eigen::Matrix3d U;
  EXPECT_FALSE(SqrtInformation(Eigen::Vector3d(1, -1, 1).asDiagonal().toDenseMatrix(), &U));
  EXPECT_FALSE(SqrtInformation(Eigen::Matrix3d::Zero(), &U));
  Eigen::Matrix3d asym = Eigen::Matrix3d::Identity();
  asym(0, 1) = 0.5;
  EXPECT_FALSE(SqrtInformation(asym, &U));
  EXPECT_FALSE(SqrtInformation(Eigen::Matrix3d::Constant(NAN), &U));
}

TEST(AngleManifold, PlusAndMinusWrapWithUnitJacobian) {
  std::unique_ptr<ceres::Manifold> m(MakeAngleManifold());
  double x = M_PI - 0.1, delta = 0.3, y = 0.0;
  ASSERT_TRUE(m->Plus(&x, &delta, &y));
  EXPECT_NEAR(y, -M_PI + 0.2, 1e-12);
  double back = 0.0;
  ASSERT_TRUE(m->Minus(&y, &x, &back));
  EXPECT_NEAR(back, 0.3, 1e-12);
  double J = 0.0;
  ASSERT_TRUE(m->PlusJacobian(&x, &J));
  EXPECT_DOUBLE_EQ(J, 1.0);
  ASSERT_TRUE(m->MinusJacobian(&x, &J));
  EXPECT_DOUBLE_EQ(J, 1.0);
}

TEST(PoseManifold, EuclideanInPositionAngleInYaw) {
  const PoseManifold m;
  ASSERT_EQ(m.AmbientSize(), 3);
  ASSERT_EQ(m.TangentSize(), 3);
  const double x[3] = {1.0, 2.0, M_PI - 0.1}, delta[3] = {0.5, -0.5, 0.3};
  double y[3], back[3], J[9];
  ASSERT_TRUE(m.Plus(x, delta, y));
  EXPECT_NEAR(y[0], 1.5, 1e-15);
  EXPECT_NEAR(y[1], 1.5, 1e-15);
  EXPECT_NEAR(y[2], -M_PI + 0.2, 1e-12);
  ASSERT_TRUE(m.Minus(y, x, back));
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(back[k], delta[k], 1e-12);
  ASSERT_TRUE(m.PlusJacobian(x, J));
  EXPECT_TRUE((Eigen::Map<Eigen::Matrix3d>(J).isIdentity(0.0)));
}

TEST(DcsLoss, WeightIsDcsScaleSquaredAndDerivativesAreConsistent) {
  const double phi = 2.0;
  const DcsLoss loss(phi);
  for (double s : {0.0, 0.5, 2.0, 3.0, 10.0, 1e4}) {
    double rho[3];
    loss.Evaluate(s, rho);
    const double k = std::min(1.0, 2 * phi / (phi + s));  // Agarwal et al. 2013, eq. 13
    EXPECT_NEAR(rho[1], k * k, 1e-12) << s;
    const double h = 1e-6 * std::max(1.0, s);
    double rp[3], rm[3];
    loss.Evaluate(s + h, rp);
    loss.Evaluate(std::max(0.0, s - h), rm);
    if (s > phi + h || s + h < phi) {
      EXPECT_NEAR(rho[1], (rp[0] - rm[0]) / (s + h - std::max(0.0, s - h)), 1e-6 * std::max(1.0, rho[1]));
      EXPECT_NEAR(rho[2], (rp[1] - rm[1]) / (s + h - std::max(0.0, s - h)), 1e-6);
    }
  }
  double below[3], above[3];  // continuous at s = Phi
  loss.Evaluate(phi, below);
  loss.Evaluate(phi * (1 + 1e-12), above);
  EXPECT_NEAR(below[0], above[0], 1e-9);
  EXPECT_NEAR(below[1], above[1], 1e-9);
}

// chi2 at each public graph's initial guess (VERTEX lines, or the odometry chain for
// edges-only files) against the reference computed independently.
TEST(Chi2, MatchesReferenceInitialValuesOfPublicGraphs) {
  const auto refs = testing::LoadReferenceValues(SLAMBOX_SOURCE_DIR);
  if (refs.empty()) GTEST_SKIP() << "public data (refs/reference_values.tsv) not found; set SLAMBOX_DATA";
  int checked = 0;
  for (const auto& [name, ref] : refs) {
    const std::string path = testing::PublicDataFile(SLAMBOX_SOURCE_DIR, "posegraph/" + name);
    if (path.empty()) continue;
    PoseGraphFile file = ReadPoseGraph(path);
    ASSERT_EQ(file.has_initial_guess, ref.init_source == "VERTEX_SE2") << name;
    if (!file.has_initial_guess) file.graph.poses = SpanningTreeInitialization(file.graph);
    EXPECT_NEAR(Chi2(file.graph), ref.chi2_init, 1e-9 * ref.chi2_init) << name;
    ++checked;
  }
  if (checked == 0) GTEST_SKIP() << "no public pose graph files found next to refs/reference_values.tsv";
  EXPECT_GE(checked, 4);
}

// The iSAM copy of M3500: the reference converts its square-root information 44.72 to
// information 2000 and evaluates chi2 along the odometry chain.
TEST(Chi2, MatchesReferenceInitialValueOfIsamManhattan) {
  const auto refs = testing::LoadReferenceValues(SLAMBOX_SOURCE_DIR);
  const std::string path = testing::PublicDataFile(SLAMBOX_SOURCE_DIR, "posegraph/manhattanOlson3500_isam.txt");
  if (path.empty() || !refs.count("manhattanOlson3500.txt"))
    GTEST_SKIP() << "posegraph/manhattanOlson3500_isam.txt or its reference row not found; set SLAMBOX_DATA";
  PoseGraphFile file = ReadPoseGraph(path);
  EXPECT_NEAR(file.graph.edges[0].information(0, 0), 2000.0, 1e-3);
  file.graph.poses = SpanningTreeInitialization(file.graph);
  const double chi2_init = refs.at("manhattanOlson3500.txt").chi2_init;
  EXPECT_NEAR(Chi2(file.graph), chi2_init, 1e-6 * chi2_init);
}

}  // namespace
}  // namespace slambox
