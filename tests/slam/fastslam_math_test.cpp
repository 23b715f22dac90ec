// FastSLAM's per-landmark math against hand-computed values, FastSLAM 2.0's proposal
// against the information form, and low-variance resampling's statistics.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <random>

#include "slam/landmark_ekf.hpp"
#include "slam/particle_weights.hpp"

namespace slambox {
namespace {

const Eigen::Matrix2d kR = Eigen::Vector2d(0.01, 0.0025).asDiagonal();  // sigma 0.1 m, 0.05 rad

LandmarkGaussian Landmark(Eigen::Vector2d mean, Eigen::Matrix2d cov) {
  LandmarkGaussian lm;
  lm.mean = mean;
  lm.covariance = cov;
  return lm;
}

// Pose at the origin, landmark at (2, 0) with Sigma = diag(0.04, 0.09): H = dh/dm =
// [[1, 0], [0, 1/2]], Q = H Sigma H^T + R = diag(0.05, 0.025). z = (2.1, 0.05) gives
// nu = (0.1, 0.05), nu^T Q^-1 nu = 0.2 + 0.1 = 0.3, K = Sigma H^T Q^-1 = diag(0.8, 1.8),
// mu' = (2.08, 0.09), Sigma' = (I - K H) Sigma = diag(0.008, 0.009).
TEST(LandmarkEkf, LikelihoodAndUpdateMatchHandComputedValues) {
  const LandmarkGaussian lm = Landmark({2, 0}, Eigen::Vector2d(0.04, 0.09).asDiagonal());
  const LandmarkMeasurement m = MeasureLandmark(SE2(), lm, {2.1, 0.05}, kR);
  EXPECT_NEAR(m.innovation.x(), 0.1, 1e-12);
  EXPECT_NEAR(m.innovation.y(), 0.05, 1e-12);
  EXPECT_TRUE(m.Q.isApprox(Eigen::Matrix2d(Eigen::Vector2d(0.05, 0.025).asDiagonal()), 1e-12));
  EXPECT_NEAR(m.log_likelihood, -std::log(2 * M_PI) - 0.5 * std::log(0.05 * 0.025) - 0.5 * 0.3, 1e-12);
  const LandmarkGaussian up = UpdateLandmark(lm, m);
  EXPECT_NEAR(up.mean.x(), 2.08, 1e-12);
  EXPECT_NEAR(up.mean.y(), 0.09, 1e-12);
  EXPECT_TRUE(up.covariance.isApprox(Eigen::Matrix2d(Eigen::Vector2d(0.008, 0.009).asDiagonal()), 1e-12));
}

TEST(LandmarkEkf, InnovationWrapsTheBearingAtPi) {
  // landmark straight behind: predicted bearing -pi; measured +pi - 0.01 is 0.01 away
  const LandmarkGaussian lm = Landmark({-3, 0}, Eigen::Matrix2d::Identity() * 1e-4);
  const LandmarkMeasurement m = MeasureLandmark(SE2(), lm, {3.0, M_PI - 0.01}, kR);
  EXPECT_NEAR(m.innovation.y(), -0.01, 1e-12);
}

// Pose (1, 2, pi/2), z = (2, 0): the landmark is at (1, 4); d m / d z = [[0, -2], [1, 0]],
// so Sigma = J R J^T = diag(4 * 0.0025, 0.01) = diag(0.01, 0.01).
TEST(LandmarkEkf, InitializationMatchesHandComputedValues) {
  const LandmarkGaussian lm = InitializeLandmark(SE2(1, 2, M_PI / 2), {2, 0}, kR);
  EXPECT_NEAR(lm.mean.x(), 1, 1e-12);
  EXPECT_NEAR(lm.mean.y(), 4, 1e-12);
  EXPECT_TRUE(lm.covariance.isApprox(Eigen::Matrix2d::Identity() * 0.01, 1e-9));
  EXPECT_EQ(lm.counter, 1);
}

// Thrun Table 13.3, lines 12-13 (information form): Sigma_x = (H_x^T Q^-1 H_x + P^-1)^-1,
// mu_x = x + Sigma_x H_x^T Q^-1 nu with Q = H_m Sigma H_m^T + R; the likelihood is
// N(nu; 0, H_x P H_x^T + Q).
TEST(PoseProposal, KalmanFormEqualsTheInformationForm) {
  const SE2 x(0.5, -0.3, 0.4);
  Eigen::Matrix3d P;
  P << 0.02, 0.003, 0.001, 0.003, 0.03, -0.002, 0.001, -0.002, 0.01;
  Eigen::Matrix2d S;
  S << 0.05, 0.01, 0.01, 0.03;
  const LandmarkGaussian lm = Landmark({4, 2}, S);
  const Eigen::Vector2d z(3.9, 0.05);
  PoseProposal prop{x, P};
  const double ll = ConditionProposal(prop, lm, z, kR);

  const double dx = 4 - x.x, dy = 2 - x.y, q = dx * dx + dy * dy, r = std::sqrt(q);
  Eigen::Matrix<double, 2, 3> Hx;
  Hx << -dx / r, -dy / r, 0, dy / q, -dx / q, -1;
  Eigen::Matrix2d Hm;
  Hm << dx / r, dy / r, -dy / q, dx / q;
  const Eigen::Matrix2d Q = Hm * S * Hm.transpose() + kR;
  const Eigen::Vector2d nu(z.x() - r, NormalizeAngle(z.y() - (std::atan2(dy, dx) - x.theta)));
  const Eigen::Matrix3d Sx = (Hx.transpose() * Q.inverse() * Hx + P.inverse()).inverse();
  const Eigen::Vector3d mu = x.vector() + Sx * Hx.transpose() * Q.inverse() * nu;
  EXPECT_TRUE(prop.covariance.isApprox(Sx, 1e-9));
  EXPECT_TRUE(prop.mean.vector().isApprox(mu, 1e-9));
  EXPECT_NEAR(ll, GaussianLogLikelihood(nu, Hx * P * Hx.transpose() + Q), 1e-12);
  EXPECT_NEAR(ll, ProposalLogLikelihood({x, P}, lm, z, kR), 1e-12);
}

TEST(PoseProposal, ZeroPriorCovarianceLeavesThePoseUnchanged) {
  PoseProposal prop{SE2(1, 1, 0.2), Eigen::Matrix3d::Zero()};
  ConditionProposal(prop, Landmark({5, 3}, Eigen::Matrix2d::Identity() * 0.01), {4.0, 0.3}, kR);
  EXPECT_TRUE(prop.mean.vector().isApprox(Eigen::Vector3d(1, 1, 0.2)));
  EXPECT_TRUE(prop.covariance.isZero());
}

TEST(ParticleWeights, NormalizationAndEffectiveSampleSize) {
  const std::vector<double> w = NormalizeLogWeights({-1000.0, -1000.0 + std::log(3.0)});
  EXPECT_NEAR(w[0], 0.25, 1e-12);
  EXPECT_NEAR(w[1], 0.75, 1e-12);
  EXPECT_NEAR(EffectiveSampleSize({0.25, 0.25, 0.25, 0.25}), 4.0, 1e-12);
  EXPECT_NEAR(EffectiveSampleSize({1.0, 0.0, 0.0}), 1.0, 1e-12);
  EXPECT_NEAR(EffectiveSampleSize(w), 1.0 / (0.0625 + 0.5625), 1e-12);
}

// Systematic resampling draws particle i floor(M w_i) or ceil(M w_i) times, and M w_i
// times on average. Over T seeded trials the mean count has standard error <= 0.5/sqrt(T)
// (a count that takes two adjacent values has variance <= 1/4); we allow 5 of them.
TEST(ParticleWeights, LowVarianceResamplingPreservesTheWeightsExpectation) {
  const std::vector<double> w = {0.37, 0.21, 0.155, 0.0625, 0.0025, 0.2};
  const int M = static_cast<int>(w.size()), T = 20000;
  std::mt19937_64 rng(42);
  std::vector<double> mean_count(M, 0.0);
  for (int trial = 0; trial < T; ++trial) {
    const std::vector<int> chosen = LowVarianceResample(w, rng);
    ASSERT_EQ(static_cast<int>(chosen.size()), M);
    std::vector<int> count(M, 0);
    for (int i : chosen) ++count[i];
    for (int i = 0; i < M; ++i) {
      ASSERT_GE(count[i], std::floor(M * w[i])) << i;
      ASSERT_LE(count[i], std::ceil(M * w[i])) << i;
      mean_count[i] += count[i] / static_cast<double>(T);
    }
  }
  for (int i = 0; i < M; ++i) EXPECT_NEAR(mean_count[i], M * w[i], 5 * 0.5 / std::sqrt(T)) << i;
}

TEST(ParticleWeights, SampleGaussianHasTheRequestedMoments) {
  Eigen::Matrix3d C;
  C << 0.04, 0.01, 0, 0.01, 0.09, 0.005, 0, 0.005, 0.01;
  const Eigen::Vector3d mu(1, -2, 0.3);
  std::mt19937_64 rng(3);
  const int n = 40000;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d sum2 = Eigen::Matrix3d::Zero();
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d d = SampleGaussian(mu, C, rng) - mu;
    sum += d;
    sum2 += d * d.transpose();
  }
  // mean: standard error sqrt(C_ii / n); covariance entries: about sqrt(2 / n) * C scale
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(sum(i) / n, 0.0, 5 * std::sqrt(C(i, i) / n));
  EXPECT_LT(((sum2 / n) - C).cwiseAbs().maxCoeff(), 5 * std::sqrt(2.0 / n) * 0.09);
  EXPECT_EQ(SampleGaussian(mu, Eigen::Matrix3d::Zero(), rng), mu);
}

}  // namespace
}  // namespace slambox

namespace slambox {
namespace {
TEST(PoseProposal, PreparedLikelihoodEqualsTheDirectOne) {
  Eigen::Matrix3d P;
  P << 0.02, 0.003, 0.001, 0.003, 0.03, -0.002, 0.001, -0.002, 0.01;
  const LandmarkGaussian lm = Landmark({-4, 0.1}, Eigen::Matrix2d::Identity() * 0.02);
  for (const Eigen::Matrix3d& prior_cov : {Eigen::Matrix3d(Eigen::Matrix3d::Zero()), P}) {
    const PoseProposal prior{SE2(0.5, -0.3, 0.4), prior_cov};
    const PredictedMeasurement pm = PredictMeasurement(prior, lm, kR);
    for (const Eigen::Vector2d& z : {Eigen::Vector2d(4.4, -2.8), Eigen::Vector2d(4.6, 2.9)})
      EXPECT_NEAR(LogLikelihood(pm, z), ProposalLogLikelihood(prior, lm, z, kR), 1e-10);
    if (prior_cov.isZero()) {  // FastSLAM 1.0: the same as the landmark EKF's likelihood
      EXPECT_NEAR(LogLikelihood(pm, {4.4, -2.8}), MeasureLandmark(prior.mean, lm, {4.4, -2.8}, kR).log_likelihood, 1e-10);
    }
  }
}
}  // namespace
}  // namespace slambox
