// The odometry prior of ICP: its residual's Jacobian and angle wrap, the fused step as the
// exact minimizer of scan + prior (finite-difference gradient), and ICP with a prior:
// a well-constrained scan wins, a degenerate direction follows the prior.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "slam/icp.hpp"
#include "slam/icp_prior.hpp"
#include "tests/support/synthetic_scan.hpp"

namespace slambox {
namespace {

using testing::CorridorWalls;
using testing::RayCastScan;
using testing::RoomWalls;

Eigen::Matrix3d RandomSpd(std::mt19937_64& rng, double scale) {
  std::normal_distribution<double> n(0, 1);
  Eigen::Matrix3d M;
  for (int i = 0; i < 9; ++i) M(i / 3, i % 3) = n(rng);
  return scale * (M * M.transpose() + 0.1 * Eigen::Matrix3d::Identity());
}

double FusedCost(const SE2& T, const SE2& T_scan, const Eigen::Matrix3d& A, const IcpPrior& prior) {
  const Eigen::Vector3d d(T.x - T_scan.x, T.y - T_scan.y, NormalizeAngle(T.theta - T_scan.theta));
  const Eigen::Vector3d e = PriorResidual(prior, T);
  return d.dot(A * d) + e.dot(prior.information * e);
}

TEST(IcpPrior, ResidualJacobianMatchesFiniteDifferencesAcrossTheWrap) {
  for (const SE2& mean : {SE2(0.3, -0.2, 0.4), SE2(1.0, 2.0, M_PI - 0.01), SE2(-1.0, 0.5, -M_PI + 0.005)}) {
    const IcpPrior prior{mean, Eigen::Matrix3d::Identity()};
    for (const SE2& T : {SE2(0.1, 0.1, 0.3), SE2(1.0, 2.0, -M_PI + 0.02), SE2(0.0, 0.0, M_PI - 0.003)}) {
      const Eigen::Vector3d e = PriorResidual(prior, T);
      EXPECT_LE(std::abs(e.z()), M_PI);  // wrapped: the short way round
      const double h = 1e-6;
      for (int k = 0; k < 3; ++k) {
        Eigen::Vector3d x(T.x, T.y, T.theta), xp = x, xm = x;
        xp(k) += h, xm(k) -= h;
        const Eigen::Vector3d ep = PriorResidual(prior, SE2(xp.x(), xp.y(), xp.z()));
        const Eigen::Vector3d em = PriorResidual(prior, SE2(xm.x(), xm.y(), xm.z()));
        Eigen::Vector3d column = ep - em;
        column.z() = NormalizeAngle(column.z());
        column /= 2 * h;
        EXPECT_LT((column - Eigen::Vector3d::Unit(k)).norm(), 1e-6) << "k=" << k << " column " << column.transpose();
      }
    }
  }
  // Across +-pi: headings 0.02 rad apart on either side of the cut differ by 0.02, not 2 pi.
  const IcpPrior wrap{SE2(0, 0, M_PI - 0.01), Eigen::Matrix3d::Identity()};
  EXPECT_NEAR(PriorResidual(wrap, SE2(0, 0, -M_PI + 0.01)).z(), 0.02, 1e-12);
}

TEST(IcpPrior, FusedStepIsTheMinimizerOfScanPlusPrior) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix3d A = RandomSpd(rng, 1e4), Omega = RandomSpd(rng, 1e2);
    const SE2 T_scan(0.1 * trial, -0.05 * trial, NormalizeAngle(0.3 * trial));
    const IcpPrior prior{T_scan * SE2(0.05, -0.03, 0.04), Omega};
    const SE2 T = FuseWithPrior(T_scan, A, prior);
    const double h = 1e-6;
    Eigen::Vector3d gradient;
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d xp(T.x, T.y, T.theta), xm = xp;
      xp(k) += h, xm(k) -= h;
      gradient(k) = (FusedCost(SE2(xp.x(), xp.y(), xp.z()), T_scan, A, prior) -
                     FusedCost(SE2(xm.x(), xm.y(), xm.z()), T_scan, A, prior)) / (2 * h);
    }
    // Compared with the gradient's size at the scan's solution (the prior's pull there).
    const Eigen::Vector3d e0 = PriorResidual(prior, T_scan);
    EXPECT_LT(gradient.norm(), 1e-5 * (2 * Omega * e0).norm()) << "trial " << trial << " " << gradient.transpose();
  }
}

TEST(IcpPrior, FusionAcrossTheWrapAndTheLimits) {
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  // Equal weights, headings either side of +-pi: the fused heading is at the cut, not near 0.
  const SE2 fused = FuseWithPrior(SE2(0, 0, M_PI - 0.01), I, IcpPrior{SE2(0, 0, -M_PI + 0.03), I});
  EXPECT_NEAR(std::abs(NormalizeAngle(fused.theta - (-M_PI + 0.01))), 0.0, 1e-12) << fused.theta;
  // No prior information: the scan's solution; no scan information along x: the prior's x.
  const SE2 T_scan(0.4, -0.1, 0.2);
  const SE2 same = FuseWithPrior(T_scan, 1e3 * I, IcpPrior{SE2(1, 1, 1), Eigen::Matrix3d::Zero()});
  EXPECT_NEAR(same.x, T_scan.x, 1e-15);
  EXPECT_NEAR(same.theta, T_scan.theta, 1e-15);
  const Eigen::Matrix3d A = Eigen::Vector3d(0.0, 1e6, 1e6).asDiagonal();
  const SE2 along = FuseWithPrior(T_scan, A, IcpPrior{SE2(0.7, 0.0, 0.0), I});
  EXPECT_NEAR(along.x, 0.7, 1e-12);
  EXPECT_NEAR(along.y, T_scan.y, 1e-6);
  EXPECT_NEAR(along.theta, T_scan.theta, 1e-6);
}

struct ScanPair {
  ScanPoints source;
  IcpTarget target;
};
ScanPair MakePair(const std::vector<Segment>& walls, const SE2& A, const SE2& T_ts, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const LaserScanEvent a = RayCastScan(walls, A, 360, 0.01, rng);
  const LaserScanEvent b = RayCastScan(walls, A * T_ts, 360, 0.01, rng);
  return {ScanToPoints(b), MakeScanTarget(ScanToPoints(a), a)};
}
IcpConfig P2l() {
  IcpConfig c;
  c.convergence_translation_m = 1e-6;
  c.convergence_rotation_rad = 1e-6;
  c.correspondence = IcpCorrespondence::kProjection;
  return c;
}

TEST(IcpPrior, WellConstrainedScanWinsDegenerateDirectionFollowsThePrior) {
  const SE2 T_true(0.3, 0.02, 0.01);
  // Room: a prior 6 cm / 1.7 deg off with a 5 cm / 3 deg std hardly moves the scan's answer.
  const ScanPair room = MakePair(RoomWalls(), SE2(0, 0.1, 0.0), T_true, 5);
  const IcpPrior off{SE2(0.25, 0.05, -0.02), Eigen::Vector3d(400.0, 400.0, 365.0).asDiagonal()};
  const IcpResult free = RegisterIcp(room.source.points, room.target, off.mean, P2l());
  const IcpResult with = RegisterIcp(room.source.points, room.target, off.mean, P2l(), &off);
  ASSERT_TRUE(with.converged);
  EXPECT_LT((with.T_target_source.translation() - T_true.translation()).norm(), 3e-3);
  EXPECT_LT((with.T_target_source.translation() - free.T_target_source.translation()).norm(), 1e-3);
  EXPECT_NEAR(with.T_target_source.theta, T_true.theta, 2e-3);
  EXPECT_NEAR(with.covariance(0, 0), free.covariance(0, 0), 1e-3 * free.covariance(0, 0));  // the scan's own
  // Corridor without solution remapping: along the axis only the prior holds the pose.
  IcpConfig no_remap = P2l();
  no_remap.remap_degenerate = false;
  const ScanPair corridor = MakePair(CorridorWalls(), SE2(0, 0.1, 0.0), T_true, 5);
  const IcpPrior odometry{SE2(0.27, 0.0, 0.0), Eigen::Vector3d(400.0, 400.0, 365.0).asDiagonal()};
  const IcpResult c = RegisterIcp(corridor.source.points, corridor.target, odometry.mean, no_remap, &odometry);
  ASSERT_TRUE(c.degenerate);
  EXPECT_NEAR(c.T_target_source.x, odometry.mean.x, 5e-3) << c.T_target_source.x;
  EXPECT_NEAR(c.T_target_source.y, T_true.y, 3e-3);
  EXPECT_NEAR(c.T_target_source.theta, T_true.theta, 2e-3);
}

}  // namespace
}  // namespace slambox
