#include "slam/smoother_merges.hpp"

#include "slam/data_association.hpp"
#include "slam/landmark_merge.hpp"
#include "slam/pairing_likelihood.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace slambox {

namespace {

struct Candidate {
  int a = 0, b = 0;              ///< indices into the involved landmarks (a's key < b's key)
  PointDifference unconditional;  ///< m_a - m_b before any merge (its d^2 orders the seeds)
};

/// One pair's difference under the current (conditioned) Gaussian; landmark i at rows 2i.
PointDifference Difference(const Eigen::VectorXd& x, const Eigen::MatrixXd& P, int a, int b) {
  return DifferenceOf(x, P, 2 * a, 2 * b);
}

/// mu: the landmarks other than a expected in the gate of a pair with difference covariance C.
double ExpectedOthersInGate(const Eigen::Matrix2d& C, const MergeSearchSettings& s) {
  return ExpectedInGate(C, s.gate_chi2, s.density_per_m2);
}

/// Grows a hypothesis from `seed` (see the header): its pairs (involved indices), in order.
/// Conditioning on the taken pairs (stacked difference operator H_T) without touching P:
/// with L L^T = H_T P H_T^T (block Cholesky, grown one pair at a time), a candidate c's
/// difference is N(D_c - W_c^T v, C_c - W_c^T W_c), W_c = L^-1 H_T P H_c^T, v = L^-1 H_T x —
/// the same Gaussian as ConditionOnEqual applied to (x, P) pair by pair. W_c is linear in
/// H_c, so it is kept per landmark, not per candidate: U = (L^-1 H_T P)^T, one 2-row block
/// per landmark and one 2-column block per taken pair, and W_c = U_a - U_b for c = (a, b).
/// Taking pair (a, b) as the t-th adds the block column (P H_ab^T - U_{0..t-1} W_ab) L_tt^-T,
/// O(t m) for all m landmarks, and each candidate's C and D then change by its 2 x 2 block
/// of that column: O(1) per candidate and taken pair. `U` is workspace of 2m rows and at
/// least 2 * (m / 2) columns; columns beyond the taken pairs are never read.
std::vector<std::pair<int, int>> Grow(const std::vector<Candidate>& candidates, int seed, const Eigen::MatrixXd& P,
                                      const MergeSearchSettings& s, Eigen::MatrixXd& U) {
  std::vector<Eigen::Matrix2d> C(candidates.size());  // conditioned difference covariances
  std::vector<Eigen::Vector2d> D(candidates.size());  // conditioned differences
  std::vector<int> live;                               // candidates with both landmarks free, in order
  for (size_t k = 0; k < candidates.size(); ++k)
    C[k] = candidates[k].unconditional.C, D[k] = candidates[k].unconditional.D, live.push_back(static_cast<int>(k));
  std::vector<std::pair<int, int>> taken;
  int next = seed;
  while (next >= 0) {
    const Candidate c = candidates[next];
    const Eigen::Index t = static_cast<Eigen::Index>(taken.size());  // block column of this pair
    taken.emplace_back(c.a, c.b);
    const auto touches = [&](int k) {
      const Candidate& o = candidates[k];
      return o.a == c.a || o.a == c.b || o.b == c.a || o.b == c.b;
    };
    live.erase(std::remove_if(live.begin(), live.end(), touches), live.end());
    // The new pair's block of L: L_tt = chol(C_next | taken), and its column of U.
    const Eigen::LLT<Eigen::Matrix2d> llt(0.5 * (C[next] + C[next].transpose()));
    if (llt.info() != Eigen::Success) break;  // a candidate's d^2 is finite: C was positive definite
    const Eigen::Matrix2d L_tt = llt.matrixL();
    const Eigen::Vector2d v_t = L_tt.triangularView<Eigen::Lower>().solve(D[next]);
    auto column = U.middleCols<2>(2 * t);
    column = P.middleCols<2>(2 * c.a) - P.middleCols<2>(2 * c.b);
    if (t > 0) {
      const Eigen::MatrixXd W_ab = U.block(2 * c.a, 0, 2, 2 * t) - U.block(2 * c.b, 0, 2, 2 * t);  // W_ab^T
      column.col(0).noalias() -= U.leftCols(2 * t) * W_ab.row(0).transpose();
      column.col(1).noalias() -= U.leftCols(2 * t) * W_ab.row(1).transpose();
    }
    column = column * L_tt.transpose().triangularView<Eigen::Upper>().solve(Eigen::Matrix2d::Identity());
    next = -1;
    double best = std::numeric_limits<double>::infinity();
    for (const int k : live) {
      const Candidate& o = candidates[k];
      const Eigen::Matrix2d w = U.block<2, 2>(2 * o.a, 2 * t) - U.block<2, 2>(2 * o.b, 2 * t);  // W_k^T
      C[k].noalias() -= w * w.transpose();
      D[k].noalias() -= w * v_t;
      // d^2 = D^T C^-1 D by the 2 x 2 adjugate; C positive definite iff C_00 > 0 and det C > 0.
      const double c00 = C[k](0, 0), c11 = C[k](1, 1), c01 = 0.5 * (C[k](0, 1) + C[k](1, 0));
      const double area = c00 * c11 - c01 * c01;  // det C: the gate's area up to pi gate
      if (!(c00 > 0.0 && area > 0.0) || area >= best) continue;
      const Eigen::Vector2d& d = D[k];
      const double d2 = (c11 * d.x() * d.x() - 2.0 * c01 * d.x() * d.y() + c00 * d.y() * d.y()) / area;
      if (d2 < s.gate_chi2) best = area, next = k;
    }
  }
  return taken;
}

double Cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

}  // namespace

double MapDensity(const Eigen::VectorXd& mean) {
  const int n = static_cast<int>(mean.size() / 2);
  if (n < 3) return 0.0;
  std::vector<Eigen::Vector2d> p(n);
  for (int i = 0; i < n; ++i) p[i] = mean.segment<2>(2 * i);
  std::sort(p.begin(), p.end(), [](const auto& u, const auto& v) { return u.x() < v.x() || (u.x() == v.x() && u.y() < v.y()); });
  // Andrew's monotone chain: lower then upper hull, counter-clockwise.
  std::vector<Eigen::Vector2d> hull(2 * n);
  int k = 0;
  for (int i = 0; i < n; ++i) {
    while (k >= 2 && Cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  for (int i = n - 2, lower = k + 1; i >= 0; --i) {
    while (k >= lower && Cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  double area = 0.0;  // shoelace; hull[k - 1] == hull[0]
  for (int i = 0; i + 1 < k; ++i) area += hull[i].x() * hull[i + 1].y() - hull[i + 1].x() * hull[i].y();
  area = 0.5 * std::abs(area);
  return area > 0 ? n / area : 0.0;
}

std::vector<std::pair<int, int>> FindJointMerges(const JointLandmarks& L,
                                                 const std::set<std::pair<int, int>>& seen_together,
                                                 const MergeSearchSettings& s) {
  const int n = static_cast<int>(L.keys.size());
  // Candidates: pairs never seen together whose unconditional d^2 is inside the gate.
  std::vector<std::pair<int, int>> pairs;  // landmark indices, smaller key first
  std::vector<PointDifference> differences;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) {
      const auto [a, b] = L.keys[i] < L.keys[j] ? std::pair{i, j} : std::pair{j, i};
      if (seen_together.count({L.keys[a], L.keys[b]})) continue;
      const PointDifference d = Difference(L.mean, L.covariance, a, b);
      if (d.d2 < s.gate_chi2) pairs.emplace_back(a, b), differences.push_back(d);
    }
  if (pairs.empty()) return {};
  // Only the landmarks in some candidate take part: their marginal is the sub-block.
  std::map<int, int> local;  // landmark index -> involved index
  for (const auto& [a, b] : pairs) local.emplace(a, 0), local.emplace(b, 0);
  std::vector<int> involved;
  for (auto& [index, l] : local) l = static_cast<int>(involved.size()), involved.push_back(index);
  const int m = static_cast<int>(involved.size());
  Eigen::VectorXd x(2 * m);
  Eigen::MatrixXd P(2 * m, 2 * m);
  for (int r = 0; r < m; ++r) {
    x.segment<2>(2 * r) = L.mean.segment<2>(2 * involved[r]);
    for (int c = 0; c < m; ++c) P.block<2, 2>(2 * r, 2 * c) = L.covariance.block<2, 2>(2 * involved[r], 2 * involved[c]);
  }
  std::vector<Candidate> candidates;
  for (size_t k = 0; k < pairs.size(); ++k)
    candidates.push_back({local[pairs[k].first], local[pairs[k].second], differences[k]});
  std::vector<int> order(candidates.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
  std::stable_sort(order.begin(), order.end(),
                   [&](int u, int v) { return candidates[u].unconditional.d2 < candidates[v].unconditional.d2; });

  const auto to_merges = [&](const std::vector<std::pair<int, int>>& taken) {  // involved indices -> keys
    std::vector<std::pair<int, int>> merges;
    for (const auto& [a, b] : taken) merges.emplace_back(L.keys[involved[a]], L.keys[involved[b]]);
    std::sort(merges.begin(), merges.end());
    return merges;
  };
  // Pairs whose gate alone expects fewer other landmarks than the threshold (a
  // re-observation the front end split off while certain) merge first, all at once; the
  // loop closures are decided jointly only among what is left, so pairs that are certain
  // anyway are no evidence for any hypothesis.
  const double log_threshold = std::log(s.fake_probability);
  std::vector<std::pair<int, int>> confident;
  std::vector<bool> used(m, false);
  for (const int k : order) {
    const Candidate& c = candidates[k];
    if (used[c.a] || used[c.b]) continue;
    if (std::log(ExpectedOthersInGate(c.unconditional.C, s)) >= log_threshold) continue;
    confident.emplace_back(c.a, c.b);
    used[c.a] = used[c.b] = true;
  }
  if (!confident.empty()) return to_merges(confident);
  // Otherwise every candidate seeds a hypothesis, which keeps only the pairs it explains
  // better with than without (slam/pairing_likelihood.hpp); of those below the threshold,
  // the largest wins (ties: the more likely; with k equal the density's share cancels).
  Eigen::MatrixXd U(2 * m, 2 * (m / 2));  // Grow's workspace
  std::vector<std::pair<int, int>> best;
  double best_log_ratio = -std::numeric_limits<double>::infinity();
  for (const int seed : order) {
    std::vector<std::pair<int, int>> grown = Grow(candidates, seed, P, s, U);
    if (grown.size() < best.size()) continue;  // dropping pairs cannot make it larger than the best
    const std::vector<std::pair<int, int>> kept =
        DropUnexplainedPairs(x, P, std::move(grown), s.gate_chi2, s.density_per_m2);
    const PairingLikelihood l = EvaluatePairing(x, P, kept, s.gate_chi2, s.density_per_m2);
    double log_all_wrong = 0.0;  // log prod_i min(1, mu_i)
    for (const double log_mu : l.log_expected_in_gate) log_all_wrong += std::min(0.0, log_mu);
    if (kept.empty() || !l.valid || log_all_wrong >= log_threshold) continue;
    if (kept.size() > best.size() || (kept.size() == best.size() && l.log_ratio > best_log_ratio))
      best = kept, best_log_ratio = l.log_ratio;
  }
  return to_merges(best);
}

std::vector<std::pair<int, int>> UnchallengedPairings(const JointLandmarks& L,
                                                      const std::set<std::pair<int, int>>& seen_together,
                                                      const std::vector<std::pair<int, int>>& proposals,
                                                      double gate_chi2, double keep_chi2) {
  const int n = static_cast<int>(L.keys.size());
  std::map<int, int> index;
  for (int i = 0; i < n; ++i) index[L.keys[i]] = i;
  const auto apart = [&](int i, int j) { return !seen_together.count(std::minmax(L.keys[i], L.keys[j])); };
  // Landmarks (other than `except`) in i's gate.
  const auto rivals = [&](int i, int except) {
    for (int j = 0; j < n; ++j)
      if (j != i && j != except && apart(i, j) && Difference(L.mean, L.covariance, i, j).d2 < gate_chi2) return true;
    return false;
  };
  std::vector<std::pair<double, std::pair<int, int>>> accepted;  // d^2, (i, j)
  for (const auto& [segment, paired] : proposals) {
    const auto a = index.find(segment), b = index.find(paired);
    if (a == index.end() || b == index.end() || a->second == b->second || !apart(a->second, b->second)) continue;
    const double d2 = Difference(L.mean, L.covariance, a->second, b->second).d2;
    if (d2 < keep_chi2 && !rivals(a->second, b->second) && !rivals(b->second, a->second))
      accepted.push_back({d2, {a->second, b->second}});
  }
  std::sort(accepted.begin(), accepted.end());
  std::vector<bool> used(n, false);
  std::vector<std::pair<int, int>> merges;
  for (const auto& [d2, ij] : accepted) {
    const auto [i, j] = ij;
    if (used[i] || used[j]) continue;
    used[i] = used[j] = true;
    merges.push_back(std::minmax(L.keys[i], L.keys[j]));
  }
  std::sort(merges.begin(), merges.end());
  return merges;
}

double PairsDifferenceChi2(const JointLandmarks& landmarks, const std::vector<std::pair<int, int>>& pairs) {
  std::map<int, int> index;
  for (size_t i = 0; i < landmarks.keys.size(); ++i) index[landmarks.keys[i]] = static_cast<int>(i);
  std::vector<std::pair<int, int>> indices;
  for (const auto& [a, b] : pairs) indices.emplace_back(index.at(a), index.at(b));
  const auto [D, C] = StackPairDifferences(landmarks.mean, landmarks.covariance, indices);
  const Eigen::LLT<Eigen::MatrixXd> llt(C);
  if (llt.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
  return D.dot(llt.solve(D));
}

}  // namespace slambox
