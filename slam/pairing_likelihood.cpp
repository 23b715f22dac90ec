#include "slam/pairing_likelihood.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

namespace slambox {

PairDifferences StackPairDifferences(const Eigen::VectorXd& x, const Eigen::MatrixXd& P,
                                     const std::vector<std::pair<int, int>>& pairs) {
  const int k = static_cast<int>(pairs.size());
  PairDifferences d{Eigen::VectorXd(2 * k), Eigen::MatrixXd(2 * k, 2 * k)};
  for (int i = 0; i < k; ++i) {
    d.D.segment<2>(2 * i) = x.segment<2>(2 * pairs[i].first) - x.segment<2>(2 * pairs[i].second);
    for (int j = 0; j < k; ++j) d.C.block<2, 2>(2 * i, 2 * j) = PairCrossCovariance(P, pairs[i], pairs[j]);
  }
  d.C = (0.5 * (d.C + d.C.transpose())).eval();
  return d;
}

PairingLikelihood EvaluatePairing(const Eigen::VectorXd& x, const Eigen::MatrixXd& P,
                                  const std::vector<std::pair<int, int>>& pairs, double gate_chi2,
                                  double density_per_m2) {
  const int k = static_cast<int>(pairs.size());
  PairingLikelihood r;
  const auto [D, C] = StackPairDifferences(x, P, pairs);
  const Eigen::LLT<Eigen::MatrixXd> llt(C);
  if (llt.info() != Eigen::Success) return r;
  r.valid = true;
  const double log_two_pi_density = std::log(2.0 * M_PI * density_per_m2);
  // The scalar Cholesky factor's 2 x 2 diagonal block i factors the Schur complement of
  // the pairs before it, C_i: sqrt(det C_i) = L_(2i,2i) L_(2i+1,2i+1).
  const Eigen::VectorXd log_diagonal = llt.matrixL().toDenseMatrix().diagonal().array().log();
  for (int i = 0; i < k; ++i)
    r.log_expected_in_gate.push_back(std::log(density_per_m2 * M_PI * gate_chi2) + log_diagonal(2 * i) +
                                     log_diagonal(2 * i + 1));
  // Given all the others, pair i's difference has the conditional (Schur) covariance
  // (Lambda_ii)^-1, Lambda = C^-1, and its deviation from the conditional mean is
  // (Lambda_ii)^-1 (Lambda D)_i (the leave-one-out form of Gaussian conditioning).
  const Eigen::MatrixXd Lambda = llt.solve(Eigen::MatrixXd::Identity(2 * k, 2 * k));
  const Eigen::VectorXd w = Lambda * D;
  for (int i = 0; i < k; ++i) {
    const Eigen::Matrix2d Lambda_ii = Lambda.block<2, 2>(2 * i, 2 * i);
    const Eigen::Vector2d v = w.segment<2>(2 * i);
    const double d2 = v.dot(Lambda_ii.ldlt().solve(v));
    r.log_ratio_given_rest.push_back(-0.5 * d2 + 0.5 * std::log(Lambda_ii.determinant()) - log_two_pi_density);
  }
  r.log_ratio = -0.5 * D.dot(w) - log_diagonal.sum() - k * log_two_pi_density;  // log det C / 2 = sum log L_ii
  return r;
}

std::vector<std::pair<int, int>> DropUnexplainedPairs(const Eigen::VectorXd& x, const Eigen::MatrixXd& P,
                                                      std::vector<std::pair<int, int>> pairs, double gate_chi2,
                                                      double density_per_m2) {
  while (!pairs.empty()) {
    const PairingLikelihood l = EvaluatePairing(x, P, pairs, gate_chi2, density_per_m2);
    if (!l.valid) break;
    const auto worst = std::min_element(l.log_ratio_given_rest.begin(), l.log_ratio_given_rest.end());
    if (*worst >= 0.0) break;
    pairs.erase(pairs.begin() + (worst - l.log_ratio_given_rest.begin()));
  }
  return pairs;
}

}  // namespace slambox
