// A hypothesis' likelihood against "no merges" (slam/pairing_likelihood.hpp): closed form
// for independent pairs, and the chain rule against sequential conditioning (ConditionOnEqual)
// on random joint Gaussians, in every factor and in the total.
#include "slam/pairing_likelihood.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <random>

#include "slam/data_association.hpp"
#include "slam/landmark_merge.hpp"

namespace slambox {
namespace {

constexpr double kGate = 9.21;

/// Points i at rows 2i, independent with isotropic variances.
Eigen::MatrixXd Diagonal(const std::vector<double>& variances) {
  Eigen::VectorXd v(2 * variances.size());
  for (size_t i = 0; i < variances.size(); ++i) v.segment<2>(2 * i).setConstant(variances[i]);
  return v.asDiagonal();
}

TEST(EvaluatePairing, IndependentPairsByHand) {
  // Pair (0, 1): difference (0.3, 0), C = 0.02 I; pair (2, 3): (1.5, 0), C = 2 I.
  const Eigen::VectorXd x = (Eigen::VectorXd(8) << 0, 0, -0.3, 0, 5, 5, 3.5, 5).finished();
  const Eigen::MatrixXd P = Diagonal({0.01, 0.01, 1.0, 1.0});
  const double density = 0.05;
  const PairingLikelihood l = EvaluatePairing(x, P, {{0, 1}, {2, 3}}, kGate, density);
  ASSERT_TRUE(l.valid);
  // Each factor N(D; 0, C) / density = exp(-d^2 / 2) / (2 pi sqrt(det C) density).
  const double first = -0.5 * 0.09 / 0.02 - std::log(2 * M_PI * 0.02 * density);
  const double second = -0.5 * 2.25 / 2.0 - std::log(2 * M_PI * 2.0 * density);
  EXPECT_NEAR(l.log_ratio_given_rest[0], first, 1e-12);
  EXPECT_NEAR(l.log_ratio_given_rest[1], second, 1e-12);
  EXPECT_NEAR(l.log_ratio, first + second, 1e-12);
  EXPECT_NEAR(l.log_expected_in_gate[0], std::log(density * M_PI * kGate * 0.02), 1e-12);
  EXPECT_NEAR(l.log_expected_in_gate[1], std::log(density * M_PI * kGate * 2.0), 1e-12);
  // The factor is 1 where d^2 = 2 ln(gate / (2 mu)).
  EXPECT_GT(first, 0.0);
  EXPECT_LT(second, 0.0);  // mu = 2.9 others in its gate: two landmarks explain it better
  // A landmark in two pairs makes C singular.
  EXPECT_FALSE(EvaluatePairing(x, P, {{0, 1}, {1, 0}}, kGate, density).valid);
  // No pairs: the null hypothesis itself.
  EXPECT_EQ(EvaluatePairing(x, P, {}, kGate, density).log_ratio, 0.0);
}

TEST(EvaluatePairing, ChainRuleAgreesWithSequentialConditioning) {
  std::mt19937 rng(7);
  std::normal_distribution<double> n01;
  const double density = 0.03;
  for (int trial = 0; trial < 20; ++trial) {
    const int points = 8;
    Eigen::MatrixXd A(2 * points, 2 * points);
    for (int r = 0; r < A.rows(); ++r)
      for (int c = 0; c < A.cols(); ++c) A(r, c) = n01(rng);
    const Eigen::MatrixXd P = 0.1 * A * A.transpose() + 0.05 * Eigen::MatrixXd::Identity(2 * points, 2 * points);
    Eigen::VectorXd x(2 * points);
    for (int r = 0; r < x.size(); ++r) x(r) = n01(rng);
    const std::vector<std::pair<int, int>> pairs = {{0, 5}, {3, 1}, {6, 2}, {4, 7}};
    const PairingLikelihood l = EvaluatePairing(x, P, pairs, kGate, density);
    ASSERT_TRUE(l.valid);
    // Factor by factor, each pair given the ones before it.
    Eigen::VectorXd xc = x;
    Eigen::MatrixXd Pc = P;
    double total = 0.0;
    for (size_t i = 0; i < pairs.size(); ++i) {
      const PointDifference p = DifferenceOf(xc, Pc, 2 * pairs[i].first, 2 * pairs[i].second);
      total += -0.5 * p.d2 - std::log(2 * M_PI * std::sqrt(p.C.determinant()) * density);
      EXPECT_NEAR(l.log_expected_in_gate[i], std::log(ExpectedInGate(p.C, kGate, density)), 1e-9);
      ASSERT_TRUE(ConditionOnEqual(xc, Pc, 2 * pairs[i].first, 2 * pairs[i].second));
    }
    EXPECT_NEAR(l.log_ratio, total, 1e-9);
    // Given the rest = the last factor of an order that ends with that pair.
    for (size_t i = 0; i < pairs.size(); ++i) {
      std::vector<std::pair<int, int>> rest = pairs;
      rest.erase(rest.begin() + static_cast<long>(i));
      EXPECT_NEAR(l.log_ratio_given_rest[i], l.log_ratio - EvaluatePairing(x, P, rest, kGate, density).log_ratio, 1e-9);
    }
  }
}

TEST(DropUnexplainedPairs, DropsThePairTheOthersExplainWorseThanTwoLandmarks) {
  const Eigen::VectorXd x = (Eigen::VectorXd(8) << 0, 0, -0.3, 0, 5, 5, 3.5, 5).finished();
  const Eigen::MatrixXd P = Diagonal({0.01, 0.01, 1.0, 1.0});
  EXPECT_EQ(DropUnexplainedPairs(x, P, {{2, 3}, {0, 1}}, kGate, 0.05), (std::vector<std::pair<int, int>>{{0, 1}}));
  // Ten times sparser: the same difference is more likely one landmark than two.
  EXPECT_EQ(DropUnexplainedPairs(x, P, {{2, 3}, {0, 1}}, kGate, 0.005),
            (std::vector<std::pair<int, int>>{{2, 3}, {0, 1}}));
}

}  // namespace
}  // namespace slambox
