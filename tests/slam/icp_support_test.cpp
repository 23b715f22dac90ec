// Pieces around ICP: scan to points, voxel subsampling, the adaptive gate, loop-closure
// candidates and verification, edge information caps, the occupancy grid.
#include <cmath>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "slam/adaptive_threshold.hpp"
#include "slam/edge_information.hpp"
#include "slam/loop_closure.hpp"
#include "slam/occupancy_grid_builder.hpp"
#include "slam/scan_points.hpp"

namespace slambox {
namespace {

TEST(ScanPoints, ValidBeamsOnlyAtTheirAngles) {
  LaserScanEvent scan;
  scan.angle_min_rad = -M_PI / 2;
  scan.angle_increment_rad = M_PI / 2;
  scan.range_min_m = 0.1;
  scan.range_max_m = 10;
  scan.ranges_m = {1.0, 2.0, 10.0, 0.05};
  scan.valid = {1, 1, 0, 1};  // beam 2 is a miss, beam 3 below range_min
  const ScanPoints p = ScanToPoints(scan);
  ASSERT_EQ(p.points.size(), 2u);
  EXPECT_NEAR(p.points[0].x(), 0.0, 1e-12);
  EXPECT_NEAR(p.points[0].y(), -1.0, 1e-12);
  EXPECT_NEAR(p.points[1].x(), 2.0, 1e-12);
  EXPECT_EQ(p.beam[1], 1);
  EXPECT_EQ(ScanToPoints(scan, {.range_max_m = 1.5}).points.size(), 1u);
}

TEST(ScanPoints, VoxelSubsampleKeepsThePointNearestEachCellsCentroid) {
  // cell (0, 0): centroid (0.02, 0.02), nearest point 1; cell (1, 0): two points at the same
  // distance from their centroid, the earlier one is kept; cells in order of first arrival.
  const std::vector<Eigen::Vector2d> pts = {{0.01, 0.01}, {0.02, 0.025}, {0.11, 0.0}, {-0.01, 0.0},
                                            {0.12, 0.02}, {0.03, 0.025}};
  const std::vector<int> kept = VoxelSubsample(pts, 0.1);
  EXPECT_EQ(kept, (std::vector<int>{1, 2, 3}));
}

// A 180-degree scan along a straight corridor (walls 0.7 m either side), 0.25-degree beams,
// range noise 2 cm, thinned to 5 cm voxels as the front end's local map is. The walls drawn
// by the kept points must stay parallel to the true ones. Keeping the first point of each
// voxel in beam order tilted them: along a wall the sweep enters each voxel from one side,
// and the first point in is one whose range noise pushed it across the voxel's edge, i.e.
// off the wall by an amount that changes with the incidence angle (+0.23 and +0.28 mrad for
// the two walls here, the same way: the corridor turned, and a front end registered to such
// maps drifted by about 0.03 deg/m; now 0.05 and -0.001 mrad).
TEST(ScanPoints, VoxelSubsampleDoesNotTurnANoisyWall) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 0.02);
  double slope_sum[2] = {0, 0};
  const int draws = 200;
  for (int d = 0; d < draws; ++d) {
    std::vector<Eigen::Vector2d> pts;
    for (int b = -360; b <= 360; ++b) {
      const double bearing = b * 0.25 * M_PI / 180.0;
      if (std::abs(std::sin(bearing)) < 0.7 / 30.0) continue;  // beyond a 30 m range
      const double r = 0.7 / std::abs(std::sin(bearing)) + noise(rng);
      pts.emplace_back(r * std::cos(bearing), r * std::sin(bearing));
    }
    double sx[2] = {0, 0}, sy[2] = {0, 0}, sxx[2] = {0, 0}, sxy[2] = {0, 0}, n[2] = {0, 0};
    for (int k : VoxelSubsample(pts, 0.05)) {
      const Eigen::Vector2d& p = pts[static_cast<size_t>(k)];
      if (p.x() < 1.0 || p.x() > 10.0) continue;
      const int w = p.y() > 0;
      sx[w] += p.x(), sy[w] += p.y(), sxx[w] += p.x() * p.x(), sxy[w] += p.x() * p.y(), ++n[w];
    }
    for (int w = 0; w < 2; ++w) slope_sum[w] += (n[w] * sxy[w] - sx[w] * sy[w]) / (n[w] * sxx[w] - sx[w] * sx[w]);
  }
  for (int w = 0; w < 2; ++w) EXPECT_NEAR(slope_sum[w] / draws, 0.0, 1.2e-4) << slope_sum[w] / draws << (w ? "left" : "right") << " wall";
}

TEST(AdaptiveThreshold, GateIsThreeSigmaOfModelDeviation) {
  AdaptiveThreshold th;
  th.config.max_range_m = 10;
  EXPECT_DOUBLE_EQ(CorrespondenceGate(th), th.config.initial_gate_m);
  UpdateThreshold(th, SE2(0.001, 0, 0), SE2(0.5, 0, 0));  // standstill prediction: skipped
  EXPECT_EQ(th.samples, 0);
  UpdateThreshold(th, SE2(0.1, 0, 0), SE2(0.12, 0, 0));
  UpdateThreshold(th, SE2(0.1, 0, 0), SE2(0.1, 0, 0.01));
  const double d2 = 2 * 10 * std::sin(0.005);
  EXPECT_NEAR(CorrespondenceGate(th), std::max(3 * std::sqrt((0.02 * 0.02 + d2 * d2) / 2), th.config.min_gate_m),
              1e-9);
}

TEST(LoopClosure, CandidatesNearestFirstAfterEnoughTravel) {
  const std::vector<SE2> poses = {SE2(0, 0, 0), SE2(5, 0, 0), SE2(0.3, 0.2, 0), SE2(9, 9, 0), SE2(0.1, 0, 0)};
  const std::vector<double> path = {0, 10, 20, 30, 40};
  LoopClosureConfig c;
  c.min_travel_m = 15;
  c.search_radius_m = 0.5;
  c.radius_per_travel = 0.0;
  c.min_keyframe_gap = 1;
  const auto cand = FindLoopCandidates(poses, path, 4, c);
  ASSERT_EQ(cand.size(), 2u);
  EXPECT_EQ(cand[0].keyframe, 0);  // 0.1 m away
  EXPECT_EQ(cand[1].keyframe, 2);  // 0.28 m away
  c.min_travel_m = 30;             // keyframe 2 is too recent now
  EXPECT_EQ(FindLoopCandidates(poses, path, 4, c).size(), 1u);
}

// The inverse's covariance is J C J^T with J the Jacobian of T -> T^-1 over (x, y, theta);
// J checked against central differences.
TEST(LoopClosure, InverseCovarianceMatchesNumericJacobian) {
  const SE2 T(1.3, -0.7, 2.9);
  Eigen::Matrix3d J;
  const double h = 1e-6;
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    d(k) = h;
    const SE2 p = SE2(T.x + d(0), T.y + d(1), T.theta + d(2)).inverse();
    const SE2 m = SE2(T.x - d(0), T.y - d(1), T.theta - d(2)).inverse();
    J.col(k) = Eigen::Vector3d(p.x - m.x, p.y - m.y, NormalizeAngle(p.theta - m.theta)) / (2 * h);
  }
  const Eigen::Matrix3d C = Eigen::Vector3d(0.04, 0.01, 0.002).asDiagonal();
  EXPECT_LT((InverseCovariance(T, C) - J * C * J.transpose()).cwiseAbs().maxCoeff(), 1e-8);
}

// On a chain the relative covariance is the chained composition; a certain shortcut
// (a closure) is preferred over the long way round.
TEST(LoopClosure, RelativeCovariancesFollowTheMostCertainPath) {
  PoseGraph g;
  const Eigen::Matrix3d info = Eigen::Vector3d(1e4, 1e4, 1e5).asDiagonal();
  for (int i = 0; i < 6; ++i) g.poses.push_back(SE2(i * 1.0, 0.1 * i, 0.2 * i));
  for (int i = 0; i + 1 < 6; ++i) g.edges.push_back({i, i + 1, Between(g.poses[i], g.poses[i + 1]), info, false});
  auto rel = RelativeCovariances(g, 5, {}, 1e9);
  // By hand: cov(T_3_5) = compose(T_3_4, C, T_4_5, C).
  const Eigen::Matrix3d C = info.inverse();
  const Eigen::Matrix3d c35 = ComposeCovariance(Between(g.poses[3], g.poses[4]), C, Between(g.poses[4], g.poses[5]), C);
  EXPECT_LT((rel[3] - c35).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_TRUE(rel[5].isZero());
  EXPECT_GT(rel[0].trace(), rel[3].trace());
  const double far = rel[0](0, 0) + rel[0](1, 1);
  g.edges.push_back({0, 5, Between(g.poses[0], g.poses[5]), info, true});
  rel = RelativeCovariances(g, 5, {}, 1e9);
  // Through the closure: the inverse of that one edge's covariance.
  EXPECT_LT((rel[0] - C).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT(rel[0](0, 0) + rel[0](1, 1), far);
  // Edges switched off are not used; nodes beyond max_trace are "unreached".
  std::vector<bool> use(g.edges.size(), true);
  use.back() = false;
  rel = RelativeCovariances(g, 5, use, 1e9);
  EXPECT_NEAR(rel[0](0, 0) + rel[0](1, 1), far, 1e-15);
  rel = RelativeCovariances(g, 5, use, 1e-12);
  EXPECT_EQ(rel[0](0, 0), 1e6);
}

TEST(LoopClosure, VerificationChecksEachCriterion) {
  LoopClosureConfig c;
  IcpResult r;
  r.converged = true;
  r.num_source = 100;
  r.num_inliers = 90;
  r.rms_residual_m = 0.01;
  r.T_target_source = SE2(1.0, 0, 0);
  EXPECT_TRUE(VerifyLoopClosure(r, SE2(0.9, 0, 0), 1.0, c).accepted);
  EXPECT_EQ(VerifyLoopClosure(r, SE2(-0.5, 0, 0), 1.0, c).reason, "correction beyond search radius");
  IcpResult bad = r;
  bad.degenerate = true;
  EXPECT_FALSE(VerifyLoopClosure(bad, SE2(0.9, 0, 0), 1.0, c).accepted);
  bad = r;
  bad.num_inliers = 30;
  EXPECT_EQ(VerifyLoopClosure(bad, SE2(0.9, 0, 0), 1.0, c).reason, "overlap");
  bad = r;
  bad.rms_residual_m = 0.2;
  EXPECT_EQ(VerifyLoopClosure(bad, SE2(0.9, 0, 0), 1.0, c).reason, "fitness");
}

TEST(EdgeInformation, CappedAndDegenerateDirectionFromOdometry) {
  IcpResult r;
  r.covariance = Eigen::Vector3d(1e-8, 1e-4, 1e-8).asDiagonal();  // x and theta very certain
  r.eigenvectors = Eigen::Matrix3d::Identity();
  const InformationCaps caps{0.01, 0.01};
  Eigen::Matrix3d info = IcpEdgeInformation(r, Eigen::Matrix3d::Identity(), caps);
  EXPECT_NEAR(info(0, 0), 1e4, 1e-6);  // capped at 1 / 0.01^2
  EXPECT_NEAR(info(1, 1), 1e4, 1e-6);  // 1e-4 variance is exactly the cap
  EXPECT_NEAR(info(2, 2), 1e4, 1e-6);
  // Degenerate along x (column 0): x's information comes from the odometry (sigma 0.5 m).
  r.covariance = Eigen::Vector3d(1e6, 1e-3, 1e-3).asDiagonal();
  r.degenerate = true;
  r.degenerate_dimensions = 1;
  info = IcpEdgeInformation(r, Eigen::Vector3d(0.25, 0.25, 0.25).asDiagonal(), caps);
  EXPECT_NEAR(info(0, 0), 4.0, 1e-9);
  EXPECT_NEAR(info(1, 1), 1e3, 1e-6);
  EXPECT_NEAR(info(0, 1), 0.0, 1e-9);
}

TEST(OccupancyGrid, BeamsMarkFreeAndOccupiedCells) {
  // One pose at the origin looking at a hit 1 m ahead along +x.
  const OccupancyGrid g = BuildOccupancyGrid({SE2(0.025, 0.025, 0)}, {{Eigen::Vector2d(1.0, 0.0)}},
                                             {.resolution_m = 0.05, .margin_m = 0.5});
  const auto cell = [&](double x, double y) {
    const int ix = static_cast<int>(std::floor((x - g.origin_m.x()) / g.resolution_m));
    const int iy = static_cast<int>(std::floor((y - g.origin_m.y()) / g.resolution_m));
    return g.cells[static_cast<size_t>(iy * g.width + ix)];
  };
  EXPECT_GT(cell(1.03, 0.03), 50);  // the hit
  EXPECT_LT(cell(0.5, 0.03), 50);   // passed through
  EXPECT_GE(cell(0.5, 0.03), 0);
  EXPECT_EQ(cell(0.5, 0.4), -1);    // never observed
}

}  // namespace
}  // namespace slambox
