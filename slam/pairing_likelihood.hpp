#pragma once
// How well a hypothesis of landmark pairs explains the smoother's landmarks (issue 14,
// `forest` seed 121): its likelihood against "no pair is one landmark", in the spirit of
// ML data association (Blackman & Popoli 1999, the track score; Cox & Leonard 1994).
// For pairs p_1 .. p_k with stacked differences D = (m_a1 - m_b1, ..) ~ N(0, C) if every
// pair is one point (C from the landmarks' joint covariance), against: each b_i is a
// landmark of its own, anywhere at the map's density lambda (a Poisson map, the density
// slam/smoother_merges uses), the likelihood ratio is
//   Lambda = N(D; 0, C) / lambda^k,
//   log Lambda = -D^T C^-1 D / 2 - log det(2 pi C) / 2 - k log lambda.
// It factors over the pairs in any order (chain rule), each factor
//   N(D_i; mean_i, C_i) / lambda = gate / (2 mu_i) exp(-d_i^2 / 2),
// with C_i pair i's covariance given the pairs before it and mu_i = lambda pi gate
// sqrt(det C_i) the landmarks expected in its gate: a pair is more likely one landmark than
// two iff d_i^2 < 2 ln(gate / (2 mu_i)) — the d^2 gate narrows as the gate gets crowded.
// Given all the other pairs (the last factor in an order that ends with it) this decides
// whether the hypothesis explains the data better with pair i or without it.
#include <Eigen/Core>
#include <utility>
#include <vector>

namespace slambox {

struct PairingLikelihood {
  bool valid = false;                ///< false if C is not positive definite (a pair repeats)
  double log_ratio = 0.0;            ///< log Lambda of the whole hypothesis
  std::vector<double> log_ratio_given_rest;  ///< per pair: log of its factor given every other pair
  std::vector<double> log_expected_in_gate;  ///< per pair: log mu_i given the pairs before it (in order)
};

/// Cross-covariance of two pairs' differences x_a - x_b (indices of points stacked in P, 2
/// rows each): H_u P H_v^T with H_u = [.. I .. -I ..].
inline Eigen::Matrix2d PairCrossCovariance(const Eigen::MatrixXd& P, std::pair<int, int> u, std::pair<int, int> v) {
  return P.block<2, 2>(2 * u.first, 2 * v.first) - P.block<2, 2>(2 * u.first, 2 * v.second) -
         P.block<2, 2>(2 * u.second, 2 * v.first) + P.block<2, 2>(2 * u.second, 2 * v.second);
}

/// The stacked differences D = (x_a1 - x_b1, ..) of `pairs` (indices of points stacked in
/// (x, P), 2 rows each) and their covariance C = H P H^T, H = [.. I .. -I ..] per pair
/// (symmetrized).
struct PairDifferences {
  Eigen::VectorXd D;
  Eigen::MatrixXd C;
};
PairDifferences StackPairDifferences(const Eigen::VectorXd& x, const Eigen::MatrixXd& P,
                                     const std::vector<std::pair<int, int>>& pairs);

/// Lambda of `pairs` (indices of points stacked in (x, P), 2 rows each), in their order.
PairingLikelihood EvaluatePairing(const Eigen::VectorXd& x, const Eigen::MatrixXd& P,
                                  const std::vector<std::pair<int, int>>& pairs, double gate_chi2,
                                  double density_per_m2);

/// Backward elimination: while some pair's factor given the others is below 1, drop the
/// worst (the hypothesis without it explains the data better) and re-evaluate. Keeps order.
std::vector<std::pair<int, int>> DropUnexplainedPairs(const Eigen::VectorXd& x, const Eigen::MatrixXd& P,
                                                      std::vector<std::pair<int, int>> pairs, double gate_chi2,
                                                      double density_per_m2);

}  // namespace slambox
