#include "eval/alignment.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace slambox {
namespace {

std::vector<Eigen::Vector2d> RandomPoints(int n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-10.0, 10.0);
  std::vector<Eigen::Vector2d> p;
  for (int i = 0; i < n; ++i) p.emplace_back(u(rng), u(rng));
  return p;
}

double SumSquared(const SE2& T, const std::vector<Eigen::Vector2d>& x, const std::vector<Eigen::Vector2d>& y) {
  double s = 0.0;
  for (size_t i = 0; i < x.size(); ++i) s += (T * x[i] - y[i]).squaredNorm();
  return s;
}

TEST(Alignment, RecoversKnownRigidTransform) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-M_PI, M_PI);
  for (int trial = 0; trial < 20; ++trial) {
    const SE2 T_true(3.0 * u(rng), -2.0 * u(rng), u(rng));
    const auto est = RandomPoints(2 + trial, rng);
    std::vector<Eigen::Vector2d> gt;
    for (const auto& p : est) gt.push_back(T_true * p);
    const AlignmentResult r = UmeyamaAlignment(est, gt);
    ASSERT_TRUE(r.valid);
    EXPECT_NEAR(r.T_gt_est.x, T_true.x, 1e-9);
    EXPECT_NEAR(r.T_gt_est.y, T_true.y, 1e-9);
    EXPECT_NEAR(NormalizeAngle(r.T_gt_est.theta - T_true.theta), 0.0, 1e-9);
  }
}

TEST(Alignment, IsTheLeastSquaresOptimumWithNoise) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> noise(0.0, 0.3);
  const auto est = RandomPoints(30, rng);
  const SE2 T_true(1.0, 2.0, 0.7);
  std::vector<Eigen::Vector2d> gt;
  for (const auto& p : est) gt.push_back(T_true * p + Eigen::Vector2d(noise(rng), noise(rng)));
  const AlignmentResult r = UmeyamaAlignment(est, gt);
  ASSERT_TRUE(r.valid);
  const double best = SumSquared(r.T_gt_est, est, gt);
  for (double dth : {-1e-3, 1e-3})  // any perturbation makes the fit worse
    for (double dx : {-1e-3, 0.0, 1e-3})
      EXPECT_GT(SumSquared(SE2(r.T_gt_est.x + dx, r.T_gt_est.y, r.T_gt_est.theta + dth), est, gt), best);
}

TEST(Alignment, ReflectionIsNotAllowed) {
  // Ground truth is the mirror image of the estimate: the unconstrained orthogonal fit is a
  // reflection; the reflection fix must return the best proper rotation instead.
  std::mt19937_64 rng(3);
  const auto est = RandomPoints(12, rng);
  std::vector<Eigen::Vector2d> gt;
  for (const auto& p : est) gt.emplace_back(p.x(), -p.y());
  const AlignmentResult r = UmeyamaAlignment(est, gt);
  ASSERT_TRUE(r.valid);
  const double fit = SumSquared(r.T_gt_est, est, gt);
  EXPECT_GT(fit, 1.0);  // a rotation cannot undo a mirror
  // Brute force over rotations, with the optimal translation for each: none is better.
  Eigen::Vector2d mx = Eigen::Vector2d::Zero(), my = Eigen::Vector2d::Zero();
  for (size_t i = 0; i < est.size(); ++i) {
    mx += est[i] / est.size();
    my += gt[i] / gt.size();
  }
  for (int k = 0; k < 3600; ++k) {
    const double th = -M_PI + k * (2 * M_PI / 3600);
    const Eigen::Vector2d t = my - RotationMatrix(th) * mx;
    EXPECT_GE(SumSquared(SE2(t.x(), t.y(), th), est, gt), fit - 1e-9);
  }
}

TEST(Alignment, DegenerateInputIsReported) {
  std::vector<Eigen::Vector2d> same(5, Eigen::Vector2d(1, 2));
  EXPECT_FALSE(UmeyamaAlignment(same, same).valid);
  EXPECT_FALSE(UmeyamaAlignment(std::vector<Eigen::Vector2d>{{0, 0}}, std::vector<Eigen::Vector2d>{{1, 1}}).valid);
  // Collinear points still fix a proper 2D rotation (rank 1 = m - 1).
  std::vector<Eigen::Vector2d> line = {{0, 0}, {1, 0}, {2, 0}}, turned;
  const SE2 T(5, 1, M_PI / 2);
  for (const auto& p : line) turned.push_back(T * p);
  const AlignmentResult r = UmeyamaAlignment(line, turned);
  ASSERT_TRUE(r.valid);
  EXPECT_NEAR(r.T_gt_est.theta, M_PI / 2, 1e-12);
}

TEST(Alignment, OriginAlignmentMovesFirstPoseOntoTruth) {
  const SE2 gt0(1, 2, 0.5), est0(-3, 4, -2.0);
  const SE2 T = OriginAlignment(gt0, est0);
  const SE2 moved = TransformPoses(T, {est0}).front();
  EXPECT_NEAR(moved.x, gt0.x, 1e-12);
  EXPECT_NEAR(moved.y, gt0.y, 1e-12);
  EXPECT_NEAR(NormalizeAngle(moved.theta - gt0.theta), 0.0, 1e-12);
}

}  // namespace
}  // namespace slambox
