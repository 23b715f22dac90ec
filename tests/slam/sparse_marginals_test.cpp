// Selected inversion (slam/sparse_marginals): diagonal blocks of H^-1 against the dense
// inverse on random sparse SPD matrices, and the landmark graph's marginals against
// ceres::Covariance (dense SVD) on a small noisy graph.
#include <gtest/gtest.h>

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <random>

#include "slam/sparse_marginals.hpp"

namespace slambox {
namespace {

/// A block chain (like odometry) plus random long couplings (like landmarks seen twice),
/// diagonally dominant so it is positive definite.
Eigen::SparseMatrix<double> RandomInformation(int blocks, int size, int couplings, std::mt19937& rng) {
  std::normal_distribution<double> g;
  const int n = blocks * size;
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(0, n);
  std::vector<Eigen::Triplet<double>> t;
  int row = 0;
  auto add_factor = [&](int a, int b) {  // a residual of dimension `size` touching blocks a and b
    for (int r = 0; r < size; ++r, ++row)
      for (int c = 0; c < size; ++c) {
        t.emplace_back(row, a * size + c, g(rng));
        if (b != a) t.emplace_back(row, b * size + c, g(rng));
      }
  };
  for (int k = 0; k < blocks; ++k) add_factor(k, k);
  for (int k = 0; k + 1 < blocks; ++k) add_factor(k, k + 1);
  std::uniform_int_distribution<int> pick(0, blocks - 1);
  for (int c = 0; c < couplings; ++c) add_factor(pick(rng), pick(rng));
  Eigen::SparseMatrix<double> Js(row, n);
  Js.setFromTriplets(t.begin(), t.end());
  return Eigen::SparseMatrix<double>(Js.transpose() * Js);
}

TEST(SparseMarginals, DiagonalBlocksMatchTheDenseInverse) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const int blocks = 5 + trial * 3, size = 1 + trial % 3;
    const Eigen::SparseMatrix<double> H = RandomInformation(blocks, size, trial * 2, rng);
    const Eigen::MatrixXd inverse = Eigen::MatrixXd(H).inverse();
    std::vector<std::pair<int, int>> requested;
    for (int k = 0; k < blocks; ++k) requested.emplace_back(k * size, size);
    const DiagonalBlocksOfInverse d = InverseDiagonalBlocks(H, requested);
    ASSERT_TRUE(d.ok) << trial;
    ASSERT_EQ(d.blocks.size(), requested.size());
    for (int k = 0; k < blocks; ++k) {
      const Eigen::MatrixXd expected = inverse.block(k * size, k * size, size, size);
      EXPECT_LT((d.blocks[k] - expected).norm(), 1e-9 * expected.norm()) << "trial " << trial << " block " << k;
    }
  }
}

TEST(SparseMarginals, TrailingBlockMatchesTheDenseInverse) {
  // The last 45 of 60 blocks of size 2: 90 columns, more than one 64-column chunk.
  std::mt19937 rng(11);
  const int blocks = 60, size = 2, first = 15 * size;
  for (const int couplings : {0, 40, 200}) {
    const Eigen::SparseMatrix<double> H = RandomInformation(blocks, size, couplings, rng);
    const Eigen::MatrixXd inverse = Eigen::MatrixXd(H).inverse();
    const Eigen::MatrixXd expected = inverse.bottomRightCorner(H.rows() - first, H.cols() - first);
    const Eigen::MatrixXd joint = InverseTrailingBlock(H, first);
    ASSERT_EQ(joint.rows(), expected.rows());
    EXPECT_LT((joint - expected).norm(), 1e-9 * expected.norm()) << couplings;
    EXPECT_LT((InverseTrailingBlock(H, 0) - inverse).norm(), 1e-9 * inverse.norm()) << couplings;  // all of it
  }
  Eigen::SparseMatrix<double> indefinite(2, 2);
  indefinite.insert(0, 0) = 1;
  indefinite.insert(1, 0) = 2;
  indefinite.insert(0, 1) = 2;
  indefinite.insert(1, 1) = 1;  // eigenvalues 3 and -1
  EXPECT_EQ(InverseTrailingBlock(indefinite, 1).size(), 0);
  EXPECT_EQ(InverseTrailingBlock(indefinite, 0).size(), 0);
}

TEST(SparseMarginals, ScalarClosedForm) {
  // H = [[2, 1], [1, 2]]: H^-1 = [[2, -1], [-1, 2]] / 3.
  Eigen::SparseMatrix<double> H(2, 2);
  H.insert(0, 0) = 2;
  H.insert(1, 0) = 1;
  H.insert(0, 1) = 1;
  H.insert(1, 1) = 2;
  const DiagonalBlocksOfInverse d = InverseDiagonalBlocks(H, {{0, 1}, {1, 1}, {0, 2}});
  ASSERT_TRUE(d.ok);
  EXPECT_NEAR(d.blocks[0](0, 0), 2.0 / 3.0, 1e-15);
  EXPECT_NEAR(d.blocks[1](0, 0), 2.0 / 3.0, 1e-15);
  EXPECT_NEAR(d.blocks[2](0, 1), -1.0 / 3.0, 1e-15);
}

TEST(SparseMarginals, NotPositiveDefiniteIsReported) {
  Eigen::SparseMatrix<double> H(2, 2);
  H.insert(0, 0) = 1;
  H.insert(1, 0) = 2;
  H.insert(0, 1) = 2;
  H.insert(1, 1) = 1;  // eigenvalues 3 and -1
  EXPECT_FALSE(InverseDiagonalBlocks(H, {{0, 2}}).ok);
}

/// r = A x - b with a fixed 2 x 2 A per residual over two blocks of size 2 (a linear
/// problem, so J^T J is exact and ceres::Covariance's dense SVD is the reference).
struct LinearResidual : ceres::SizedCostFunction<2, 2, 2> {
  Eigen::Matrix2d A, B;
  bool Evaluate(double const* const* x, double* r, double** jac) const override {
    const Eigen::Vector2d e = A * Eigen::Vector2d(x[0][0], x[0][1]) + B * Eigen::Vector2d(x[1][0], x[1][1]);
    r[0] = e.x();
    r[1] = e.y();
    if (jac) {
      using RowMajor2 = Eigen::Matrix<double, 2, 2, Eigen::RowMajor>;
      if (jac[0]) {
        Eigen::Map<RowMajor2> J0(jac[0]);
        J0 = A;
      }
      if (jac[1]) {
        Eigen::Map<RowMajor2> J1(jac[1]);
        J1 = B;
      }
    }
    return true;
  }
};

TEST(SparseMarginals, InformationMatrixFromCeresMatchesCeresCovariance) {
  std::mt19937 rng(3);
  std::normal_distribution<double> g;
  const int n = 12;
  std::vector<Eigen::Vector2d> x(n, Eigen::Vector2d::Zero());
  ceres::Problem problem;
  for (auto& v : x) problem.AddParameterBlock(v.data(), 2);
  problem.SetParameterBlockConstant(x[0].data());
  auto add = [&](int a, int b) {
    auto* f = new LinearResidual;
    f->A << g(rng), g(rng), g(rng), g(rng);
    f->B << g(rng), g(rng), g(rng), g(rng);
    problem.AddResidualBlock(f, nullptr, x[a].data(), x[b].data());
  };
  for (int k = 0; k + 1 < n; ++k) add(k, k + 1);
  add(0, 5);
  add(3, 9);
  add(2, 11);
  std::vector<double*> free_blocks;
  for (int k = 1; k < n; ++k) free_blocks.push_back(x[k].data());
  const Eigen::SparseMatrix<double> H = InformationMatrix(problem, free_blocks);
  ASSERT_EQ(H.rows(), 2 * (n - 1));
  std::vector<std::pair<int, int>> requested;
  for (int k = 0; k < n - 1; ++k) requested.emplace_back(2 * k, 2);
  const DiagonalBlocksOfInverse d = InverseDiagonalBlocks(H, requested);
  ASSERT_TRUE(d.ok);

  ceres::Covariance::Options o;
  o.algorithm_type = ceres::DENSE_SVD;
  ceres::Covariance covariance(o);
  std::vector<std::pair<const double*, const double*>> pairs;
  for (double* b : free_blocks) pairs.emplace_back(b, b);
  ASSERT_TRUE(covariance.Compute(pairs, &problem));
  for (int k = 0; k < n - 1; ++k) {
    Eigen::Matrix<double, 2, 2, Eigen::RowMajor> C;
    covariance.GetCovarianceBlock(free_blocks[k], free_blocks[k], C.data());
    EXPECT_LT((d.blocks[k] - Eigen::Matrix2d(C)).norm(), 1e-9 * C.norm()) << k;
  }
}

}  // namespace
}  // namespace slambox
