#include "eval/landmark_map.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "eval/assignment.hpp"

namespace slambox {
namespace {

double BruteForceMinCost(const Eigen::MatrixXd& c) {
  // Assign min(n, m) pairs: permute the larger side.
  const bool rows_small = c.rows() <= c.cols();
  const int small = static_cast<int>(std::min(c.rows(), c.cols())), large = static_cast<int>(std::max(c.rows(), c.cols()));
  std::vector<int> perm(large);
  std::iota(perm.begin(), perm.end(), 0);
  double best = 1e300;
  do {
    double s = 0.0;
    for (int i = 0; i < small; ++i) s += rows_small ? c(i, perm[i]) : c(perm[i], i);
    best = std::min(best, s);
  } while (std::next_permutation(perm.begin(), perm.end()));
  return best;
}

TEST(Assignment, MatchesBruteForceOnRandomInstances) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0.0, 10.0);
  std::uniform_int_distribution<int> size(1, 6);
  for (int trial = 0; trial < 300; ++trial) {
    const int n = size(rng), m = size(rng);
    Eigen::MatrixXd c(n, m);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < m; ++j) c(i, j) = trial % 3 == 0 ? std::floor(u(rng) / 3) : u(rng);  // ties too
    const std::vector<int> a = SolveAssignment(c);
    ASSERT_EQ(static_cast<int>(a.size()), n);
    double cost = 0.0;
    std::vector<char> used(m, 0);
    int assigned = 0;
    for (int i = 0; i < n; ++i) {
      if (a[i] < 0) continue;
      ASSERT_FALSE(used[a[i]]);
      used[a[i]] = 1;
      cost += c(i, a[i]);
      ++assigned;
    }
    EXPECT_EQ(assigned, std::min(n, m));
    EXPECT_NEAR(cost, BruteForceMinCost(c), 1e-9) << n << "x" << m;
  }
}

TEST(Ospa, HandComputed) {
  const std::vector<Eigen::Vector2d> X = {{0, 0}}, Y = {{0, 0}, {10, 0}};
  EXPECT_NEAR(OspaDistance(X, Y, 1.0, 2.0), std::sqrt(0.5), 1e-12);  // (0 + 1^2 * 1) / 2
  EXPECT_NEAR(OspaDistance(Y, X, 1.0, 2.0), std::sqrt(0.5), 1e-12);  // symmetric
  EXPECT_EQ(OspaDistance({}, {}, 1.0, 2.0), 0.0);
  EXPECT_EQ(OspaDistance({}, Y, 3.0, 2.0), 3.0);
  // Two points each, both 0.5 m off: sqrt((0.25 + 0.25) / 2) = 0.5; order 1 also 0.5.
  const std::vector<Eigen::Vector2d> A = {{0, 0}, {5, 5}}, B = {{5, 5.5}, {0.5, 0}};
  EXPECT_NEAR(OspaDistance(A, B, 2.0, 2.0), 0.5, 1e-12);
  EXPECT_NEAR(OspaDistance(A, B, 2.0, 1.0), 0.5, 1e-12);
}

std::vector<TrueLandmark> Truth() { return {{0, {0, 0}, 0.1}, {1, {4, 0}, 0.1}, {2, {4, 3}, 0.1}}; }

TEST(LandmarkMap, KnownIdsHandComputed) {
  std::vector<LandmarkEstimate> est(2);
  est[0].id = 0;
  est[0].position = {0.3, 0.4};  // 0.5 m off
  est[0].covariance = Eigen::Matrix2d::Identity() * 0.25;
  est[0].has_covariance = true;
  est[1].id = 2;
  est[1].position = {4, 3};
  const LandmarkMapResult r = EvaluateLandmarkMap(est, Truth(), SE2());
  EXPECT_TRUE(r.by_id);
  ASSERT_EQ(r.matches.size(), 2u);
  EXPECT_NEAR(r.rmse_m, std::sqrt(0.25 / 2), 1e-12);
  EXPECT_EQ(r.missed, 1);
  EXPECT_EQ(r.spurious, 0);
  EXPECT_NEAR(r.anees, 0.25 / 0.25, 1e-12);  // only the first has a covariance
  EXPECT_TRUE(std::isnan(r.matches[1].nees));
}

TEST(LandmarkMap, AlignmentIsAppliedBeforeErrors) {
  // The estimate lives in a frame rotated and shifted by T_est_gt; aligning undoes it exactly.
  const SE2 T_gt_est(1.0, -2.0, 0.6);
  std::vector<LandmarkEstimate> est;
  for (const auto& t : Truth()) {
    LandmarkEstimate l;
    l.id = t.id;
    l.position = T_gt_est.inverse() * t.position;
    est.push_back(l);
  }
  const LandmarkMapResult r = EvaluateLandmarkMap(est, Truth(), T_gt_est);
  EXPECT_NEAR(r.rmse_m, 0.0, 1e-12);
  EXPECT_NEAR(r.ospa_m, 0.0, 1e-12);
}

TEST(LandmarkMap, OptimalAssignmentWithoutIdsCountsSpuriousAndMissed) {
  std::vector<LandmarkEstimate> est(3);
  est[0].id = 100;
  est[0].position = {4.1, 3.0};   // -> true 2
  est[1].id = 101;
  est[1].position = {0.0, 0.2};   // -> true 0
  est[2].id = 102;
  est[2].position = {20.0, 20.0};  // clutter: farther than the cutoff from everything
  const LandmarkMapResult r = EvaluateLandmarkMap(est, Truth(), SE2(), {.ospa_cutoff_m = 1.0});
  EXPECT_FALSE(r.by_id);
  ASSERT_EQ(r.matches.size(), 2u);
  EXPECT_EQ(r.spurious, 1);
  EXPECT_EQ(r.missed, 1);
  EXPECT_NEAR(r.rmse_m, std::sqrt((0.01 + 0.04) / 2), 1e-12);
  // OSPA: 3 vs 3, matched 0.1 and 0.2, the third pair cut off at 1: sqrt((0.01 + 0.04 + 1) / 3).
  EXPECT_NEAR(r.ospa_m, std::sqrt((0.01 + 0.04 + 1.0) / 3), 1e-12);
}

}  // namespace
}  // namespace slambox
