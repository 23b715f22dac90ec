#pragma once
// Marginal covariances of a least-squares problem without ceres::Covariance: the
// information matrix H = J^T J at the solution (Ceres' own Jacobian, loss functions
// applied as ceres::Covariance does), its sparse Cholesky factor P H P^T = L L^T (Eigen's
// SimplicialLLT, AMD ordering: deterministic), and Takahashi's selected inversion on the
// pattern of L (Takahashi, Fagan & Chen 1973; Rue & Martino 2007, Sec. 2): with
// Z = (L L^T)^-1, for j from n-1 down to 0 and every i > j in the pattern of column j,
//   Z_ij = -(1 / L_jj) sum_{k > j, L_kj != 0} L_kj Z_ik,
//   Z_jj = 1 / L_jj^2 - (1 / L_jj) sum_{k > j, L_kj != 0} L_kj Z_kj,
// where every Z_ik needed lies in the pattern again (the rows of a column of L form a
// clique of the filled graph). This gives every entry of H^-1 on L's pattern, among them
// all diagonal blocks of the parameter blocks, in O(sum_j |L_*j|^2) and no n x n storage.
#include <ceres/problem.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <utility>
#include <vector>

namespace slambox {

/// H = J^T J of `problem` at its current parameter values over `blocks` (in this order,
/// tangent-space columns; blocks not listed are held constant).
Eigen::SparseMatrix<double> InformationMatrix(ceres::Problem& problem, const std::vector<double*>& blocks);

struct DiagonalBlocksOfInverse {
  bool ok = false;                     ///< false: H is not positive definite
  std::vector<Eigen::MatrixXd> blocks;  ///< per requested (offset, size): that block of H^-1
};

/// The requested diagonal blocks (offset, size) of H^-1 for a symmetric positive definite
/// H (only its lower triangle is read).
DiagonalBlocksOfInverse InverseDiagonalBlocks(const Eigen::SparseMatrix<double>& H,
                                              const std::vector<std::pair<int, int>>& blocks);

/// The joint block of H^-1 over its trailing rows and columns [first, n) (a landmark
/// graph's landmarks, after the poses): the inverse of the Schur complement
/// S = H_bb - H_ba H_aa^-1 H_ab. Only H_aa is factored (sparse Cholesky); for a landmark
/// graph it is the odometry chain's block-tridiagonal information, whose factor has no fill
/// whatever loop closures the landmarks make, so the cost is (n - first) substitutions
/// along the chain and one dense Cholesky of S. Empty if H is not positive definite.
Eigen::MatrixXd InverseTrailingBlock(const Eigen::SparseMatrix<double>& H, int first);

}  // namespace slambox
