#include "eval/consistency.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <random>

namespace slambox {
namespace {

TEST(Nees, HandComputed) {
  Eigen::Matrix3d P = Eigen::Vector3d(1.0, 4.0, 0.25).asDiagonal();
  EXPECT_NEAR(PoseNees(SE2(0, 0, 0), SE2(1, 2, 0.5), P), 3.0, 1e-12);  // 1 + 1 + 1
  Eigen::Matrix2d L;
  L << 2.0, 1.0, 1.0, 2.0;  // inverse = [[2, -1], [-1, 2]] / 3
  EXPECT_NEAR(LandmarkNees({0, 0}, {1, 1}, L), (2 - 1 - 1 + 2) / 3.0, 1e-12);
}

TEST(Nees, UsesTheWrappedAngle) {
  const Eigen::Matrix3d P = Eigen::Vector3d(1.0, 1.0, 0.01).asDiagonal();
  // pi - 0.05 vs -pi + 0.05: the heading error is 0.1 rad, NEES 0.1^2 / 0.01 = 1.
  EXPECT_NEAR(PoseNees(SE2(0, 0, M_PI - 0.05), SE2(0, 0, -M_PI + 0.05), P), 1.0, 1e-9);
  EXPECT_EQ(PoseNees(SE2(1, 2, -M_PI), SE2(1, 2, -M_PI), P), 0.0);
}

TEST(Nees, RejectsInvalidCovariance) {
  EXPECT_TRUE(std::isnan(PoseNees(SE2(), SE2(1, 0, 0), Eigen::Matrix3d::Zero())));
  Eigen::Matrix3d indefinite = Eigen::Vector3d(1.0, -1.0, 1.0).asDiagonal();
  EXPECT_TRUE(std::isnan(PoseNees(SE2(), SE2(1, 0, 0), indefinite)));
  Eigen::Matrix3d nan = Eigen::Matrix3d::Identity();
  nan(0, 0) = std::nan("");
  EXPECT_TRUE(std::isnan(PoseNees(SE2(), SE2(1, 0, 0), nan)));
}

// A simulated Gaussian estimator: error e = L z with P = L L^T (correlated), z ~ N(0, I),
// heading near the +-pi wrap so the wrapped difference matters.
struct GaussianEstimator {
  Eigen::Matrix3d P;
  Eigen::Matrix3d L;
  std::mt19937_64 rng;
  std::normal_distribution<double> n01{0.0, 1.0};
  explicit GaussianEstimator(std::uint64_t seed) : rng(seed) {
    Eigen::Matrix3d A;
    A << 0.3, 0.1, 0.02, -0.1, 0.2, 0.01, 0.05, 0.0, 0.05;
    P = A * A.transpose();
    L = P.llt().matrixL();
  }
  double Draw(double overconfidence = 1.0) {
    const SE2 truth(5.0, -2.0, M_PI - 0.01);
    const Eigen::Vector3d e = L * Eigen::Vector3d(n01(rng), n01(rng), n01(rng));
    const SE2 est(truth.x + e.x(), truth.y + e.y(), truth.theta + e.z());
    return PoseNees(truth, est, P / overconfidence);
  }
};

TEST(Nees, ConsistentEstimatorIsInsideTheBandAtTheAdvertisedRate) {
  GaussianEstimator g(42);
  const int steps = 4000;
  std::vector<double> nees;
  double sum = 0.0;
  for (int k = 0; k < steps; ++k) {
    nees.push_back(g.Draw());
    sum += nees.back();
  }
  const NeesBand band = AneesBand(3, 1, 0.95);
  // Binomial(4000, 0.95): sigma = 0.0034; 4 sigma bound.
  EXPECT_NEAR(FractionInside(nees, band), 0.95, 4 * std::sqrt(0.95 * 0.05 / steps));
  // Mean NEES ~ 3 with sigma sqrt(6 / 4000) = 0.039.
  EXPECT_NEAR(sum / steps, 3.0, 4 * std::sqrt(6.0 / steps));
}

TEST(Nees, AneesOverFiftyRunsStaysInTheBand) {
  GaussianEstimator g(7);
  const int runs = 50, steps = 400;
  std::vector<std::vector<double>> nees(runs, std::vector<double>(steps));
  for (auto& run : nees)
    for (double& v : run) v = g.Draw();
  const AneesResult r = AneesOverRuns(nees, 3);
  EXPECT_NEAR(r.band.lo, 2.36, 0.005);
  EXPECT_NEAR(r.band.hi, 3.72, 0.005);
  EXPECT_NEAR(r.fraction_inside, 0.95, 4 * std::sqrt(0.95 * 0.05 / steps));

  // An estimator claiming 4x less variance than it has is caught.
  std::vector<std::vector<double>> over(runs, std::vector<double>(steps));
  for (auto& run : over)
    for (double& v : run) v = g.Draw(4.0);
  EXPECT_LT(AneesOverRuns(over, 3).fraction_inside, 0.05);
}

}  // namespace
}  // namespace slambox
