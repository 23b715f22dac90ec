#include "slam/sparse_marginals.hpp"

#include <ceres/crs_matrix.h>

#include <Eigen/Cholesky>
#include <Eigen/SparseCholesky>
#include <algorithm>

namespace slambox {

Eigen::SparseMatrix<double> InformationMatrix(ceres::Problem& problem, const std::vector<double*>& blocks) {
  ceres::Problem::EvaluateOptions options;
  options.parameter_blocks = blocks;
  options.apply_loss_function = true;
  options.num_threads = 1;
  ceres::CRSMatrix J;
  problem.Evaluate(options, nullptr, nullptr, nullptr, &J);
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(J.values.size());
  for (int r = 0; r < J.num_rows; ++r)
    for (int k = J.rows[r]; k < J.rows[r + 1]; ++k) t.emplace_back(r, J.cols[k], J.values[k]);
  Eigen::SparseMatrix<double> Js(J.num_rows, J.num_cols);
  Js.setFromTriplets(t.begin(), t.end());
  return Eigen::SparseMatrix<double>(Js.transpose() * Js);
}

DiagonalBlocksOfInverse InverseDiagonalBlocks(const Eigen::SparseMatrix<double>& H,
                                              const std::vector<std::pair<int, int>>& blocks) {
  DiagonalBlocksOfInverse out;
  Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> llt(H);
  if (llt.info() != Eigen::Success) return out;
  // P H P^T = L L^T; column-major L, so column j's rows are contiguous and sorted.
  const Eigen::SparseMatrix<double> L = llt.matrixL();
  const int n = static_cast<int>(L.cols());
  const int* outer = L.outerIndexPtr();
  const int* inner = L.innerIndexPtr();
  const double* value = L.valuePtr();
  std::vector<double> Z(L.nonZeros(), 0.0);  // Z on the pattern of L (lower triangle)
  bool in_pattern = true;
  double outside = 0.0;
  auto at = [&](int r, int c) -> double& {  // Z_rc for r >= c, in the pattern of column c
    const int* first = inner + outer[c];
    const int* last = inner + outer[c + 1];
    const int* it = std::lower_bound(first, last, r);
    if (it == last || *it != r) {  // cannot happen for L's own cliques; a requested block off the pattern
      in_pattern = false;
      return outside;
    }
    return Z[it - inner];
  };
  auto sym = [&](int r, int c) -> double& { return r >= c ? at(r, c) : at(c, r); };
  // Column j with off-diagonal rows r_1 < ... < r_m needs Z(r_p, r_q) for all p, q; for
  // q <= p those are in column r_q (whose pattern contains r_q .. r_m, the clique
  // property), so one merge scan of column r_q yields them all, and each serves both
  // Z(r_p, j) (through L_{r_q j}) and, for p > q, Z(r_q, j) (through L_{r_p j}).
  std::vector<double> acc;
  for (int j = n - 1; j >= 0; --j) {
    const int begin = outer[j], end = outer[j + 1];  // begin: the diagonal
    const double Ljj = value[begin];
    const int m = end - begin - 1;
    acc.assign(m, 0.0);
    for (int q = 0; q < m; ++q) {
      const int rq = inner[begin + 1 + q];
      int pos = outer[rq];
      const int pos_end = outer[rq + 1];
      for (int p = q; p < m; ++p) {
        const int rp = inner[begin + 1 + p];
        while (pos < pos_end && inner[pos] < rp) ++pos;
        if (pos == pos_end || inner[pos] != rp) {  // not a clique: cannot happen for a Cholesky pattern
          in_pattern = false;
          continue;
        }
        const double z = Z[pos];
        acc[p] += value[begin + 1 + q] * z;
        if (p > q) acc[q] += value[begin + 1 + p] * z;
      }
    }
    double s = 0.0;
    for (int p = 0; p < m; ++p) {
      Z[begin + 1 + p] = -acc[p] / Ljj;
      s += value[begin + 1 + p] * Z[begin + 1 + p];
    }
    Z[begin] = 1.0 / (Ljj * Ljj) - s / Ljj;
  }
  // Back to the original order: (H^-1)_ab = Z_{p(a) p(b)} with p the permutation's indices.
  const auto& perm = llt.permutationP().indices();
  for (const auto& [offset, size] : blocks) {
    Eigen::MatrixXd B(size, size);
    for (int a = 0; a < size; ++a)
      for (int b = 0; b < size; ++b) B(a, b) = sym(perm[offset + a], perm[offset + b]);
    out.blocks.push_back(B);
  }
  out.ok = in_pattern;
  return out;
}

Eigen::MatrixXd InverseTrailingBlock(const Eigen::SparseMatrix<double>& H, int first) {
  const int n = static_cast<int>(H.rows()), m = n - first;
  if (m <= 0 || first < 0) return {};
  Eigen::MatrixXd S = Eigen::MatrixXd(H.bottomRightCorner(m, m));
  if (first > 0) {
    const Eigen::SparseMatrix<double> Haa = H.topLeftCorner(first, first);
    const Eigen::SparseMatrix<double> Hab = H.topRightCorner(first, m);
    Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> llt(Haa);
    if (llt.info() != Eigen::Success) return {};
    constexpr int kColumnsPerSolve = 64;  // bounds the dense right-hand side to 64 x first
    for (int c0 = 0; c0 < m; c0 += kColumnsPerSolve) {
      const int width = std::min(kColumnsPerSolve, m - c0);
      const Eigen::MatrixXd Y = llt.solve(Eigen::MatrixXd(Hab.middleCols(c0, width)));  // H_aa^-1 H_ab
      S.middleCols(c0, width) -= Hab.transpose() * Y;
    }
  }
  S = 0.5 * (S + S.transpose());
  const Eigen::LLT<Eigen::MatrixXd> schur(S);
  if (schur.info() != Eigen::Success) return {};
  const Eigen::MatrixXd inverse = schur.solve(Eigen::MatrixXd::Identity(m, m));
  return 0.5 * (inverse + inverse.transpose());
}

}  // namespace slambox
