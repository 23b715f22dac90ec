// The iterated EKF update (IteratedUpdateState): one iteration is the EKF's update bit for
// bit; at convergence it is the maximum of the posterior (the gradient of the negative log
// posterior, by central differences, vanishes), which the EKF's single step is not when the
// heading is uncertain; bearings and heading wrap at +-pi exactly as away from it; and with a
// step gate, an update whose EKF step the prior can carry stays the EKF's bit for bit while one
// of many sigmas is iterated to the maximum.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "slam/ekf_slam_filter.hpp"
#include "slam/range_bearing.hpp"

namespace slambox {
namespace {

/// A robot at `pose` with a heading sigma of `sigma_theta` and `n` landmarks 4-10 m away.
EkfSlamState UncertainState(std::mt19937_64& rng, const SE2& pose, int n, double sigma_theta) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  EkfSlamState s = MakeInitialState(pose);
  s.mean.conservativeResize(3 + 2 * n);
  for (int j = 0; j < n; ++j) {
    const double r = 7.0 + 3.0 * u(rng), b = 1.2 * u(rng) + 2.0 * M_PI * j / n;
    s.mean.segment<2>(3 + 2 * j) = pose.translation() + r * Eigen::Vector2d(std::cos(pose.theta + b), std::sin(pose.theta + b));
  }
  Eigen::MatrixXd A = Eigen::MatrixXd::NullaryExpr(3 + 2 * n, 3 + 2 * n, [&] { return 0.05 * u(rng); });
  s.covariance = A * A.transpose() + 0.01 * Eigen::MatrixXd::Identity(3 + 2 * n, 3 + 2 * n);
  s.covariance(2, 2) += sigma_theta * sigma_theta;
  return s;
}

/// Measurements of every landmark from `truth` (the state's landmarks moved by `shift`).
std::vector<LandmarkMeasurement> Measure(const EkfSlamState& s, const SE2& truth, const Eigen::Vector2d& shift) {
  std::vector<LandmarkMeasurement> m;
  for (int j = 0; j < s.NumLandmarks(); ++j) m.push_back({j, PredictObservation(truth, s.Landmark(j) + shift).z});
  return m;
}

std::vector<LinearizedObservation> LinearizeAt(const EkfSlamState& s, const std::vector<LandmarkMeasurement>& m) {
  std::vector<LinearizedObservation> lin;
  for (const LandmarkMeasurement& x : m) {
    const ObservationPrediction p = PredictObservation(s.Pose(), s.Landmark(x.landmark));
    lin.push_back({x.landmark, Innovation(x.z, p.z), p.J_z_pose, p.J_z_landmark});
  }
  return lin;
}

/// Negative log posterior (times 2): (x - x̂)^T P^-1 (x - x̂) + sum nu_j^T R^-1 nu_j, wrapped.
double Cost(const Eigen::VectorXd& x, const EkfSlamState& prior, const std::vector<LandmarkMeasurement>& m,
            const Eigen::Matrix2d& R) {
  Eigen::VectorXd d = x - prior.mean;
  d(2) = NormalizeAngle(d(2));
  double c = d.dot(prior.covariance.ldlt().solve(d));
  const SE2 pose{x(0), x(1), x(2)};
  for (const LandmarkMeasurement& z : m) {
    const Eigen::Vector2d nu = Innovation(z.z, PredictObservation(pose, x.segment<2>(3 + 2 * z.landmark)).z);
    c += nu.dot(R.ldlt().solve(nu));
  }
  return c;
}

Eigen::VectorXd Gradient(const Eigen::VectorXd& x, const EkfSlamState& prior, const std::vector<LandmarkMeasurement>& m,
                         const Eigen::Matrix2d& R) {
  Eigen::VectorXd g(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::VectorXd a = x, b = x;
    a(i) += 1e-6;
    b(i) -= 1e-6;
    g(i) = (Cost(a, prior, m, R) - Cost(b, prior, m, R)) / 2e-6;
  }
  return g;
}

/// A robot at (0, 0, 0.1) with heading sigma `sigma_theta` and four landmarks (landmark 0
/// new-ish: variance + 4 m^2); measured from a truth far off in heading, the linearization at
/// this prior is poor.
EkfSlamState HeadingOffPrior(double sigma_theta) {
  std::mt19937_64 rng(7);
  EkfSlamState prior = UncertainState(rng, SE2(0.0, 0.0, 0.1), 4, sigma_theta);
  prior.covariance.block<2, 2>(3, 3) += 4.0 * Eigen::Matrix2d::Identity();
  return prior;
}

const Eigen::Matrix2d kR = Eigen::Vector2d(0.1 * 0.1, std::pow(M_PI / 180.0, 2)).asDiagonal();

TEST(EkfIteratedUpdate, OneIterationIsTheEkfUpdateBitForBit) {
  std::mt19937_64 rng(3);
  const EkfSlamState prior = UncertainState(rng, SE2(1.0, -2.0, 0.4), 5, 0.2);
  const std::vector<LandmarkMeasurement> m = Measure(prior, SE2(1.3, -1.8, 0.55), {0.2, -0.1});
  EkfSlamState ekf = prior, iekf = prior;
  const EkfUpdateResult a = UpdateState(ekf, LinearizeAt(ekf, m), kR);
  const EkfUpdateResult b = IteratedUpdateState(iekf, m, kR, 1);
  ASSERT_TRUE(a.applied && b.applied);
  EXPECT_EQ(a.nis, b.nis);
  EXPECT_EQ(a.dof, b.dof);
  EXPECT_TRUE(ekf.mean == iekf.mean);
  EXPECT_TRUE(ekf.covariance == iekf.covariance);
}

TEST(EkfIteratedUpdate, ConvergesToThePosteriorMaximumWhereTheEkfStepDoesNot) {
  // Heading sigma 0.35 rad (20 deg) and a truth 0.3 rad off: the linearization at the prior
  // is poor (Bailey et al. 2006's regime).
  const EkfSlamState prior = HeadingOffPrior(0.35);
  const std::vector<LandmarkMeasurement> m = Measure(prior, SE2(0.4, 0.3, 0.4), {0.0, 0.0});
  EkfSlamState ekf = prior, iekf = prior;
  ASSERT_TRUE(UpdateState(ekf, LinearizeAt(ekf, m), kR).applied);
  ASSERT_TRUE(IteratedUpdateState(iekf, m, kR, 20).applied);
  const double g_ekf = Gradient(ekf.mean, prior, m, kR).norm(), g_iekf = Gradient(iekf.mean, prior, m, kR).norm();
  EXPECT_GT(g_ekf, 10.0);  // the EKF's step stops far from the maximum
  EXPECT_LT(g_iekf, 1e-3 * g_ekf);
  EXPECT_LT(Cost(iekf.mean, prior, m, kR), Cost(ekf.mean, prior, m, kR));
  // The covariance stays symmetric positive definite and shrinks below the prior's.
  EXPECT_TRUE(iekf.covariance.isApprox(iekf.covariance.transpose(), 0.0));
  EXPECT_EQ(Eigen::LLT<Eigen::MatrixXd>(iekf.covariance).info(), Eigen::Success);
  EXPECT_LT(iekf.covariance(2, 2), prior.covariance(2, 2));
}

/// The robot part of the EKF step from `prior` (squared Mahalanobis length under P_rr).
double EkfStepChi2(const EkfSlamState& prior, const std::vector<LandmarkMeasurement>& m) {
  EkfSlamState ekf = prior;
  UpdateState(ekf, LinearizeAt(ekf, m), kR);
  Eigen::Vector3d d = ekf.mean.head<3>() - prior.mean.head<3>();
  d(2) = NormalizeAngle(d(2));
  return d.dot(prior.covariance.topLeftCorner<3, 3>().ldlt().solve(d));
}

TEST(EkfIteratedUpdate, StepGateKeepsTheEkfStepItCanCarryBitForBit) {
  // A truth within the prior's spread: the EKF step is short, the gate (chi2_3(0.99) = 11.34)
  // does not open and the result is UpdateState's exactly, with one linearization.
  std::mt19937_64 rng(3);
  const EkfSlamState prior = UncertainState(rng, SE2(1.0, -2.0, 0.4), 5, 0.2);
  const std::vector<LandmarkMeasurement> m = Measure(prior, SE2(1.05, -1.95, 0.45), {0.0, 0.0});
  ASSERT_LT(EkfStepChi2(prior, m), 11.34);
  EkfSlamState ekf = prior, gated = prior;
  const EkfUpdateResult a = UpdateState(ekf, LinearizeAt(ekf, m), kR);
  const EkfUpdateResult b = IteratedUpdateState(gated, m, kR, 20, 11.34);
  EXPECT_EQ(b.iterations, 1);
  EXPECT_EQ(a.nis, b.nis);
  EXPECT_TRUE(ekf.mean == gated.mean);
  EXPECT_TRUE(ekf.covariance == gated.covariance);
}

TEST(EkfIteratedUpdate, StepGateIteratesAStepOfManySigmas) {
  // A re-sighting after a drift: heading sigma 0.12 rad, truth 0.6 rad (5 sigma) off. The
  // EKF step is many sigmas long, the gate opens and the result is the fully iterated one
  // (the posterior's maximum), not the EKF's.
  const EkfSlamState prior = HeadingOffPrior(0.12);
  const std::vector<LandmarkMeasurement> m = Measure(prior, SE2(0.4, 0.3, 0.7), {0.0, 0.0});
  const double chi2 = EkfStepChi2(prior, m);
  ASSERT_GT(chi2, 11.34);
  EkfSlamState full = prior, gated = prior, closed = prior;
  IteratedUpdateState(full, m, kR, 20);
  const EkfUpdateResult r = IteratedUpdateState(gated, m, kR, 20, 11.34);
  EXPECT_GT(r.iterations, 2);
  EXPECT_TRUE(full.mean == gated.mean);
  EXPECT_TRUE(full.covariance == gated.covariance);
  // A gate just above this step's length keeps the EKF step: the test is on that length.
  EXPECT_EQ(IteratedUpdateState(closed, m, kR, 20, chi2 * 1.001).iterations, 1);
  EXPECT_LT(Gradient(gated.mean, prior, m, kR).norm(), 1e-3 * Gradient(closed.mean, prior, m, kR).norm());
}

TEST(EkfIteratedUpdate, WrapsAtPiAsAwayFromIt) {
  // The same problem twice: heading near +pi with the truth across the wrap, and rotated by
  // -pi about the origin (heading near 0). Ranges and bearings are unchanged by the
  // rotation; x, y and the landmarks change sign, so P' = T P T^T with T = diag(-1, -1, 1, -1, ...).
  std::mt19937_64 rng(11);
  EkfSlamState at_pi = UncertainState(rng, SE2(2.0, 1.0, M_PI - 0.01), 4, 0.2);
  const SE2 truth(2.1, 0.9, NormalizeAngle(M_PI + 0.15));
  const std::vector<LandmarkMeasurement> m = Measure(at_pi, truth, {0.0, 0.0});
  const Eigen::Index n = at_pi.mean.size();
  Eigen::VectorXd t = -Eigen::VectorXd::Ones(n);
  t(2) = 1.0;
  EkfSlamState at_zero = at_pi;
  at_zero.mean = t.asDiagonal() * at_pi.mean;
  at_zero.mean(2) = NormalizeAngle(at_pi.mean(2) - M_PI);
  at_zero.covariance = t.asDiagonal() * at_pi.covariance * t.asDiagonal();
  ASSERT_TRUE(IteratedUpdateState(at_pi, m, kR, 20).applied);
  ASSERT_TRUE(IteratedUpdateState(at_zero, m, kR, 20).applied);
  EXPECT_LT(at_pi.mean(2), -2.9);                                 // crossed the wrap to the truth's side
  EXPECT_NEAR(NormalizeAngle(at_pi.mean(2) - truth.theta), 0.0, 0.02);  // and found the truth's heading
  EXPECT_NEAR(NormalizeAngle(at_zero.mean(2) + M_PI - at_pi.mean(2)), 0.0, 1e-9);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (i == 2) continue;
    EXPECT_NEAR(at_zero.mean(i), -at_pi.mean(i), 1e-9) << i;
  }
  EXPECT_LT((at_zero.covariance - t.asDiagonal() * at_pi.covariance * t.asDiagonal()).norm(), 1e-9);
}

}  // namespace
}  // namespace slambox
