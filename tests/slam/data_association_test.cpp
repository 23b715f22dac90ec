// Data association: two-gate nearest neighbour and JCBB on crafted states, and the
// chi-square quantile against tabulated values.
#include "core/chi_square.hpp"
#include "slam/data_association.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "slam/range_bearing.hpp"

namespace slambox {
namespace {

/// Robot at the origin facing +x, well known except for 1 m of lateral (y) uncertainty;
/// two well-mapped landmarks 1 m apart across the line of sight, 10 m ahead.
EkfSlamState AmbiguousState() {
  EkfSlamState s = MakeInitialState(SE2(0, 0, 0));
  s.mean.conservativeResize(7);
  s.mean.tail<4>() << 10.0, 0.0, 10.0, 1.0;
  s.covariance = Eigen::MatrixXd::Zero(7, 7);
  s.covariance.diagonal() << 1e-4, 1.0, 1e-8, 1e-4, 1e-4, 1e-4, 1e-4;
  return s;
}

const Eigen::Matrix2d kR = Eigen::Vector2d(0.05 * 0.05, 0.002 * 0.002).asDiagonal();

/// What a robot truly at (0, y_true, 0) measures of landmark `index`.
Eigen::Vector2d Measure(const EkfSlamState& s, int index, double y_true) {
  return PredictObservation(SE2(0.0, y_true, 0.0), s.Landmark(index)).z;
}

TEST(DataAssociation, JcbbFindsTheJointlyCompatibleHypothesisWhereNearestNeighbourFails) {
  // The robot is truly 0.6 m to the right: landmark 0 appears 0.6 m left of where it
  // is mapped, i.e. 0.4 m from landmark 1, so nearest neighbour gives observation 0 to
  // landmark 1 (and then has nothing consistent for observation 1). Only the pairing
  // (0->0, 1->1) explains both observations with one robot offset.
  const EkfSlamState s = AmbiguousState();
  const std::vector<Eigen::Vector2d> z = {Measure(s, 0, -0.6), Measure(s, 1, -0.6)};
  const AssociationGates gates;
  // Both observations are individually compatible with both landmarks.
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) EXPECT_LT(MahalanobisSquared(s, j, z[i], kR), gates.accept_chi2);

  const Association nn = AssociateNearestNeighbour(s, z, kR, gates);
  EXPECT_EQ(nn.landmark[0], 1);
  EXPECT_EQ(nn.landmark[1], Association::kDiscard);

  const Association jcbb = AssociateJcbb(s, z, kR, gates);
  EXPECT_EQ(jcbb.landmark[0], 0);
  EXPECT_EQ(jcbb.landmark[1], 1);
  EXPECT_LT(JointMahalanobisSquared(s, z, kR, {{0, 0}, {1, 1}}), ChiSquareQuantile(0.99, 4));
  EXPECT_GT(JointMahalanobisSquared(s, z, kR, {{0, 1}, {1, 0}}), 100.0);
}

TEST(DataAssociation, TwoGatesSeparateMatchAmbiguousAndNew) {
  EkfSlamState s = AmbiguousState();
  s.covariance(1, 1) = 1e-4;  // a well localized robot: gates are a few centimetres
  const AssociationGates gates;
  const Eigen::Vector2d exact = Measure(s, 0, 0.0);
  // Lateral offsets at 10 m: sigma of the lateral innovation ~ sqrt(2e-4 + (10*0.002)^2) = 0.024 m.
  const double sigma_lat = std::sqrt(2e-4 + 4e-4);
  auto at_offset = [&](double chi) { return Measure(s, 0, -chi * sigma_lat); };
  const std::vector<Eigen::Vector2d> z = {exact, at_offset(3.9), at_offset(8.0)};
  const Association a = AssociateNearestNeighbour(s, z, kR, gates);
  EXPECT_EQ(a.landmark[0], 0);                      // d^2 ~ 0: match
  EXPECT_EQ(a.landmark[1], Association::kDiscard);  // 9.21 < d^2 ~ 15 < 25: ambiguous
  EXPECT_EQ(a.landmark[2], Association::kNew);      // d^2 ~ 64 > 25: new landmark
  EXPECT_GT(a.nearest_chi2[1], gates.accept_chi2);
  EXPECT_LT(a.nearest_chi2[1], gates.new_chi2);
  const Association j = AssociateJcbb(s, z, kR, gates);
  EXPECT_EQ(j.landmark, a.landmark);
}

TEST(DataAssociation, EmptyMapMakesEveryObservationNew) {
  const EkfSlamState s = MakeInitialState(SE2(1, 2, 0.3));
  const std::vector<Eigen::Vector2d> z = {{3.0, 0.1}, {4.0, -2.0}};
  EXPECT_EQ(AssociateNearestNeighbour(s, z, kR, {}).landmark, std::vector<int>(2, Association::kNew));
  EXPECT_EQ(AssociateJcbb(s, z, kR, {}).landmark, std::vector<int>(2, Association::kNew));
}

TEST(DataAssociation, Chi2QuantileMatchesTables) {
  EXPECT_NEAR(ChiSquareQuantile(0.99, 2), 9.210, 0.05);
  EXPECT_NEAR(ChiSquareQuantile(0.95, 2), 5.991, 0.06);
  EXPECT_NEAR(ChiSquareQuantile(0.95, 4), 9.488, 0.05);
  EXPECT_NEAR(ChiSquareQuantile(0.99, 10), 23.209, 0.05);
  EXPECT_NEAR(ChiSquareQuantile(0.975, 30), 46.979, 0.05);
}

TEST(DataAssociation, ExpectedFalseInGateIsDensityTimesTheGateArea) {
  // S = diag(sr^2, sb^2): the gate d^2 < g is an ellipse with semi-axes sqrt(g) sr and
  // sqrt(g) sb in (range, bearing), area pi g sr sb; r dr db maps it to the plane.
  const Eigen::Matrix2d S = Eigen::Vector2d(0.3 * 0.3, 0.05 * 0.05).asDiagonal();
  EXPECT_NEAR(ExpectedFalseInGate(S, 8.0, 9.21, 0.002), 0.002 * M_PI * 9.21 * 0.3 * 0.05 * 8.0, 1e-15);
  EXPECT_EQ(ExpectedFalseInGate(S, 8.0, 9.21, 0.0), 0.0);
}

TEST(DataAssociation, JointInnovationBlocksAreTheIndividualOnes) {
  const EkfSlamState s = AmbiguousState();
  const std::vector<Eigen::Vector2d> z = {Measure(s, 0, 0.2), Measure(s, 1, 0.2)};
  const JointInnovation j = JointInnovationOf(s, z, kR, {{0, 0}, {1, 1}});
  EXPECT_LT((j.S.block<2, 2>(0, 0) - InnovationCovariance(s, 0, kR)).norm(), 1e-15);
  EXPECT_LT((j.S.block<2, 2>(2, 2) - InnovationCovariance(s, 1, kR)).norm(), 1e-15);
  EXPECT_NEAR(j.nu.segment<2>(0).dot(j.S.block<2, 2>(0, 0).inverse() * j.nu.segment<2>(0)),
              MahalanobisSquared(s, 0, z[0], kR), 1e-9);
}

TEST(DataAssociation, ConditionalInnovationIsTheInverseOfTheInformationBlock) {
  // The covariance of pair q given the others is ((S^-1)_qq)^-1 (Schur complement).
  const EkfSlamState s = AmbiguousState();
  const std::vector<Eigen::Vector2d> z = {Measure(s, 0, 0.2), Measure(s, 1, 0.2)};
  const Eigen::MatrixXd S = JointInnovationOf(s, z, kR, {{0, 0}, {1, 1}}).S;
  const auto conditional = ConditionalInnovationCovariances(S);
  ASSERT_EQ(conditional.size(), 2u);
  const Eigen::MatrixXd information = S.inverse();
  for (int q = 0; q < 2; ++q) {
    const Eigen::Matrix2d expected = information.block<2, 2>(2 * q, 2 * q).inverse();
    EXPECT_LT((conditional[q] - expected).norm(), 1e-9 * expected.norm()) << q;
  }
  // Both landmarks share the robot's 1 m lateral uncertainty: given one, the other's
  // bearing is pinned down far below its own (a loop closure on two landmarks).
  EXPECT_LT(conditional[1](1, 1), 0.01 * S(3, 3));
  // A single pair: its own S.
  const Eigen::MatrixXd S1 = JointInnovationOf(s, z, kR, {{0, 0}}).S;
  EXPECT_EQ(ConditionalInnovationCovariances(S1)[0], Eigen::Matrix2d(S1));
}

/// Robot near the origin and `n` landmarks on a ring 6-10 m away, with a dense, correlated
/// covariance (a random P = A A^T + small diagonal), as after a long drive.
EkfSlamState CorrelatedState(int n, unsigned seed) {
  std::srand(seed);
  EkfSlamState s = MakeInitialState(SE2(0.3, -0.2, 0.1));
  s.mean.conservativeResize(3 + 2 * n);
  for (int j = 0; j < n; ++j) {
    const double a = 2.0 * M_PI * j / n, r = 6.0 + 4.0 * j / n;
    s.mean.segment<2>(3 + 2 * j) << r * std::cos(a), r * std::sin(a);
  }
  const Eigen::MatrixXd A = 0.05 * Eigen::MatrixXd::Random(3 + 2 * n, 3 + 2 * n);
  s.covariance = A * A.transpose();
  s.covariance.diagonal().array() += 1e-4;
  return s;
}

TEST(DataAssociation, JointInnovationIsTheDenseProductOverTheSubState) {
  // S = H P H^T + blockdiag(R) with H the 2k x (3 + 2n) Jacobian of every pairing,
  // built densely here; JointInnovationOf assembles it from covariance blocks.
  const EkfSlamState s = CorrelatedState(6, 3);
  std::vector<Eigen::Vector2d> z;
  for (int j = 0; j < 6; ++j) z.push_back(Measure(s, j, 0.05));
  const std::vector<std::pair<int, int>> pairs = {{4, 4}, {0, 0}, {2, 3}, {5, 1}, {3, 2}};
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(10, 15);
  for (int q = 0; q < 5; ++q) {
    const ObservationPrediction p = PredictObservation(s.Pose(), s.Landmark(pairs[q].second));
    H.block<2, 3>(2 * q, 0) = p.J_z_pose;
    H.block<2, 2>(2 * q, 3 + 2 * pairs[q].second) = p.J_z_landmark;
  }
  Eigen::MatrixXd expected = H * s.covariance * H.transpose();
  for (int q = 0; q < 5; ++q) expected.block<2, 2>(2 * q, 2 * q) += kR;
  const JointInnovation j = JointInnovationOf(s, z, kR, pairs);
  EXPECT_LT((j.S - expected).norm(), 1e-12 * expected.norm());
  EXPECT_EQ(j.S, j.S.transpose());
  // A pair's conditional covariance, straight from the Schur complement.
  const auto conditional = ConditionalInnovationCovariances(j.S);
  Eigen::MatrixXd S_rest(8, 8), S_rq(8, 2);
  const std::vector<int> rest = {0, 1, 2, 3, 6, 7, 8, 9};  // all but pair 2
  for (int a = 0; a < 8; ++a) {
    for (int b = 0; b < 8; ++b) S_rest(a, b) = j.S(rest[a], rest[b]);
    S_rq.row(a) = j.S.block<1, 2>(rest[a], 4);
  }
  const Eigen::Matrix2d schur = j.S.block<2, 2>(4, 4) - S_rq.transpose() * S_rest.inverse() * S_rq;
  EXPECT_LT((conditional[2] - schur).norm(), 1e-9 * schur.norm());
}

TEST(DataAssociation, JcbbPicksTheLargestJointlyCompatibleHypothesisOfAnExhaustiveSearch) {
  // JCBB grows the joint d^2 one pairing at a time; an exhaustive search over every
  // injective assignment with the direct joint d^2 (each prefix gated, as in the tree)
  // must agree with it. Landmarks 0.6 m
  // apart and a pose with ~0.3 m of uncertainty: many individually compatible pairings.
  for (unsigned seed = 1; seed <= 6; ++seed) {
    EkfSlamState s = CorrelatedState(5, seed);
    for (int j = 0; j < 5; ++j) s.mean.segment<2>(3 + 2 * j) << 8.0, -1.2 + 0.6 * j;
    std::vector<Eigen::Vector2d> z;
    for (int j : {1, 2, 3, 4}) z.push_back(Measure(s, j, 0.25 * (seed % 3)));
    const AssociationGates gates;
    const Association a = AssociateJcbb(s, z, kR, gates);
    std::vector<std::pair<int, int>> best;
    double best_d2 = std::numeric_limits<double>::infinity();
    std::vector<int> choice(z.size(), -1);  // -1 unpaired, else landmark
    const int n = s.NumLandmarks();
    int total = 1;
    for (size_t i = 0; i < z.size(); ++i) total *= n + 1;
    for (int code = 0; code < total; ++code) {
      std::vector<std::pair<int, int>> pairs;
      std::vector<bool> used(n, false);
      bool valid = true;
      for (int i = 0, c = code; i < static_cast<int>(z.size()); ++i, c /= n + 1) {
        const int j = c % (n + 1) - 1;
        if (j < 0) continue;
        if (used[j] || MahalanobisSquared(s, j, z[i], kR) >= gates.accept_chi2) valid = false;
        used[j] = true;
        pairs.emplace_back(i, j);
      }
      if (!valid || pairs.empty()) continue;
      // JCBB's hypotheses are jointly compatible at every level of the tree: every prefix
      // (in observation order) passes its own gate.
      for (size_t k = 1; k <= pairs.size() && valid; ++k) {
        const std::vector<std::pair<int, int>> prefix(pairs.begin(), pairs.begin() + k);
        valid = JointMahalanobisSquared(s, z, kR, prefix) < ChiSquareQuantile(gates.joint_probability, 2.0 * k);
      }
      if (!valid) continue;
      const double d2 = JointMahalanobisSquared(s, z, kR, pairs);
      if (pairs.size() > best.size() || (pairs.size() == best.size() && d2 < best_d2)) {
        best = pairs;
        best_d2 = d2;
      }
    }
    ASSERT_FALSE(best.empty()) << seed;
    std::vector<int> expected(z.size(), -1);
    for (const auto& [i, j] : best) expected[i] = j;
    for (size_t i = 0; i < z.size(); ++i)
      if (expected[i] >= 0) EXPECT_EQ(a.landmark[i], expected[i]) << "seed " << seed << " observation " << i;
    EXPECT_GT(a.jcbb_nodes, 0);
  }
}

}  // namespace
}  // namespace slambox
