#include "datasets/odometry_noise_fit.hpp"

#include <gtest/gtest.h>

#include <random>

#include "core/odometry_model.hpp"

namespace slambox {
namespace {

// Covariances J M(alpha) J^T of Thrun's model itself: the fit must return alpha exactly.
std::vector<Eigen::Matrix3d> ModelCovariances(const std::vector<SE2>& increments, const std::array<double, 4>& alpha) {
  std::vector<Eigen::Matrix3d> out;
  for (const SE2& d : increments) {
    const OdometryIncrement u = Decompose(d);
    const MotionPrediction p = PredictMotion(SE2(), u);
    out.push_back(p.J_pose_increment * IncrementCovariance(u, alpha) * p.J_pose_increment.transpose());
  }
  return out;
}

std::vector<SE2> RandomIncrements(int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> step(0.1, 1.5), turn(-0.3, 0.3);
  std::vector<SE2> out;
  for (int k = 0; k < n; ++k) {
    const double t = step(rng), r1 = turn(rng), r2 = turn(rng);
    out.push_back(Compose({r1, t, r2}));
  }
  return out;
}

TEST(OdometryNoiseFit, RecoversTheModelsOwnAlpha) {
  const std::vector<SE2> inc = RandomIncrements(200, 3);
  for (const std::array<double, 4>& alpha :
       {std::array<double, 4>{0.05, 0.005, 0.05, 0.005}, std::array<double, 4>{1e-4, 3e-4, 0.013, 8e-4}}) {
    const OdometryNoiseFit fit = FitOdometryAlpha(inc, ModelCovariances(inc, alpha));
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(fit.alpha[k], alpha[k], 1e-9 * (1 + alpha[k])) << k;
    EXPECT_LT(fit.rms_residual, 1e-6 * fit.rms_file);  // round-off of the normal equations
    EXPECT_GT(fit.rms_file, 0.0);
  }
}

TEST(OdometryNoiseFit, NonNegativeWhereTheDataWantsLess) {
  // The file's covariances: the model with alpha3 only, minus a little heading variance
  // the model cannot take away. The unconstrained fit would make alpha1/alpha2 negative;
  // the non-negative one keeps them at 0 and alpha3 near its value.
  const std::vector<SE2> inc = RandomIncrements(100, 5);
  std::vector<Eigen::Matrix3d> cov = ModelCovariances(inc, {0, 0, 0.02, 0});
  for (auto& c : cov) c(2, 2) -= 1e-4;
  const OdometryNoiseFit fit = FitOdometryAlpha(inc, cov);
  for (double a : fit.alpha) EXPECT_GE(a, 0.0);
  EXPECT_EQ(fit.alpha[0], 0.0);
  EXPECT_EQ(fit.alpha[1], 0.0);
  EXPECT_NEAR(fit.alpha[2], 0.02, 1e-3);
  EXPECT_GT(fit.rms_residual, 0.0);
}

TEST(OdometryNoiseFit, EmptyInputGivesZeros) {
  const OdometryNoiseFit fit = FitOdometryAlpha({}, {});
  for (double a : fit.alpha) EXPECT_EQ(a, 0.0);
}

}  // namespace
}  // namespace slambox
