// FastSLAM's importance weights against hand-computed values: 1.0's product of 2x2
// innovation likelihoods N(nu; 0, H Sigma H^T + R) at the sampled pose (Thrun Table 13.1
// line 13), and 2.0's predictive likelihood N(z; z_hat, H_x P H_x^T + H_m Sigma H_m^T + R)
// at the motion-predicted pose, evaluated before the pose is sampled (Montemerlo 2003,
// eq. 21; Thrun Table 13.3 line 21), so it does not depend on the drawn sample.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <random>

#include "slam/fastslam_particle.hpp"
#include "slam/landmark_ekf.hpp"

namespace slambox {
namespace {

ParticleUpdateOptions KnownIds(bool fastslam2) {
  ParticleUpdateOptions o;
  o.R = Eigen::Vector2d(0.0025, 0.0004).asDiagonal();  // sigma 0.05 m, 0.02 rad
  o.fastslam2 = fastslam2;
  o.known_ids = true;
  return o;
}

// Pose at the origin; landmark 0 at (5, 0), landmark 1 at (0, 4); Sigma = 0.01 I each.
FastSlamParticle TwoLandmarks(const Eigen::Matrix3d& pose_covariance) {
  FastSlamParticle p;
  p.pose_covariance = pose_covariance;
  for (const Eigen::Vector2d& m : {Eigen::Vector2d(5, 0), Eigen::Vector2d(0, 4)}) {
    LandmarkGaussian lm;
    lm.mean = m;
    lm.covariance = Eigen::Matrix2d::Identity() * 0.01;
    SetLandmark(p.map, p.next_key++, lm);
  }
  return p;
}

double LogN2(const Eigen::Vector2d& nu, const Eigen::Vector2d& diagonal) {
  return -std::log(2 * M_PI) - 0.5 * std::log(diagonal.prod()) - 0.5 * (nu.array().square() / diagonal.array()).sum();
}

// Landmark 0 at (5, 0) seen at z = (4.7, 0.02): nu = (-0.3, 0.02). H_m = [[1, 0], [0, 1/5]],
// Q = H_m Sigma H_m^T + R = diag(0.0125, 0.0008). Landmark 1 at (0, 4), bearing pi/2,
// seen at z = (4.1, pi/2 - 0.01): nu = (0.1, -0.01), H_m = [[0, 1], [-1/4, 0]],
// Q = diag(0.0125, 0.000625 + 0.0004).
TEST(FastSlamWeight, FastSlam1IsTheProductOfTheInnovationLikelihoods) {
  FastSlamParticle p = TwoLandmarks(Eigen::Matrix3d::Zero());
  std::mt19937_64 rng(1);
  const std::vector<LandmarkObservation> scan = {{4.7, 0.02, 0}, {4.1, M_PI / 2 - 0.01, 1}};
  const ParticleUpdateSummary s = UpdateParticle(p, scan, KnownIds(false), rng);
  const double expected = LogN2({-0.3, 0.02}, {0.0125, 0.0008}) + LogN2({0.1, -0.01}, {0.0125, 0.001025});
  EXPECT_NEAR(s.log_weight_factor, expected, 1e-9);
  EXPECT_EQ(s.matched, 2);
}

// One observation of landmark 0 with P = diag(0.04, 0.04, 0.001): H_x = [[-1, 0, 0],
// [0, -1/5, -1]], H_x P H_x^T = diag(0.04, 0.04/25 + 0.001) = diag(0.04, 0.0026), so
// L = diag(0.04 + 0.01 + 0.0025, 0.0026 + 0.0004 + 0.0004) = diag(0.0525, 0.0034) and the
// weight is log N((-0.3, 0.02); 0, L) whatever pose the proposal then draws.
TEST(FastSlamWeight, FastSlam2IsThePredictiveLikelihoodBeforeSampling) {
  const Eigen::Matrix3d P = Eigen::Vector3d(0.04, 0.04, 0.001).asDiagonal();
  const double expected = LogN2({-0.3, 0.02}, {0.0525, 0.0034});
  SE2 first_sample;
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    FastSlamParticle p = TwoLandmarks(P);
    std::mt19937_64 rng(seed);
    const ParticleUpdateSummary s = UpdateParticle(p, {{4.7, 0.02, 0}}, KnownIds(true), rng);
    EXPECT_NEAR(s.log_weight_factor, expected, 1e-9) << "seed " << seed;
    if (seed == 1) first_sample = p.pose;
    else EXPECT_NE(p.pose.x, first_sample.x);  // different samples, identical weight
  }
}

// Two observations: the sequential factors (each conditioned on the ones before) are the
// chain rule of the joint predictive density N([z0; z1]; [z0_hat; z1_hat],
// J P J^T + blockdiag(Q0, Q1)), J = [H_x0; H_x1], up to the relinearization after the
// first update (small for this P).
TEST(FastSlamWeight, FastSlam2WithTwoObservationsIsTheJointPredictiveLikelihood) {
  const Eigen::Matrix3d P = Eigen::Vector3d(0.0004, 0.0004, 0.0001).asDiagonal();
  FastSlamParticle p = TwoLandmarks(P);
  std::mt19937_64 rng(4);
  const std::vector<LandmarkObservation> scan = {{4.97, 0.005, 0}, {4.02, M_PI / 2 - 0.004, 1}};
  const ParticleUpdateSummary s = UpdateParticle(p, scan, KnownIds(true), rng);

  Eigen::Matrix<double, 4, 3> J;
  J << -1, 0, 0,  //
      0, -0.2, -1,  //
      0, -1, 0,  //
      0.25, 0, -1;
  Eigen::Vector4d q(0.0125, 0.0008, 0.0125, 0.001025);
  const Eigen::Matrix4d L = J * P * J.transpose() + Eigen::Matrix4d(q.asDiagonal());
  const Eigen::Vector4d nu(-0.03, 0.005, 0.02, -0.004);
  const double joint = -2 * std::log(2 * M_PI) - 0.5 * std::log(L.determinant()) - 0.5 * nu.dot(L.inverse() * nu);
  EXPECT_NEAR(s.log_weight_factor, joint, 1e-3);
  // and it is not the likelihood at the sampled pose (FastSLAM 1.0's formula)
  FastSlamParticle at_sample = TwoLandmarks(Eigen::Matrix3d::Zero());
  at_sample.pose = p.pose;
  const double after = UpdateParticle(at_sample, scan, KnownIds(false), rng).log_weight_factor;
  EXPECT_GT(std::abs(after - joint), 1e-2);
}

}  // namespace
}  // namespace slambox
