// Correlative scan matcher: the score table's closed form and pooled bounds, branch-and-
// bound returns the exhaustive optimum on random maps, and a global match of a scan pair
// offset by about 2 m / 30 deg, where ICP from the zero guess fails.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "slam/correlative_matcher.hpp"
#include "slam/icp.hpp"
#include "tests/support/synthetic_scan.hpp"

namespace slambox {
namespace {

// Every pooled level h at (x, y) equals the max of level 0 over [x, x + 2^h) x [y, y + 2^h),
// on a lattice of cells that reaches past the table's edges.
void ExpectPooledLevelsAreWindowMaxima(const ScoreTable& t) {
  for (int h = 1; h < static_cast<int>(t.levels.size()); ++h)
    for (int y = -9; y < t.height + 2; y += 3)
      for (int x = -9; x < t.width + 2; x += 2) {
        float m = 0.0f;
        for (int dy = 0; dy < (1 << h); ++dy)
          for (int dx = 0; dx < (1 << h); ++dx) m = std::max(m, t.At(0, x + dx, y + dy));
        ASSERT_EQ(t.At(h, x, y), m) << "level " << h << " cell " << x << "," << y;
      }
}

TEST(ScoreTable, ClosedFormAroundOnePoint) {
  const Eigen::Vector2d p(0.512, -0.237);
  const ScoreTableConfig c{.resolution_m = 0.05, .sigma_m = 0.05, .levels = 3};
  const ScoreTable t = MakeScoreTable({p}, c);
  ASSERT_GT(t.width, 0);
  for (int y = 0; y < t.height; ++y)
    for (int x = 0; x < t.width; ++x) {
      const Eigen::Vector2d centre = t.origin_m + (Eigen::Vector2d(x, y) + Eigen::Vector2d::Constant(0.5)) * 0.05;
      const double d = (centre - p).norm();
      const double expected = d <= 0.15 ? std::exp(-d * d / (2 * 0.05 * 0.05)) : 0.0;
      ASSERT_NEAR(t.At(0, x, y), expected, 1e-6) << x << "," << y;
    }
  // The point's own cell scores exp(-d^2 / 2 sigma^2) at its distance to the cell centre.
  const Eigen::Vector2i cell = t.Cell(p);
  const Eigen::Vector2d centre = t.origin_m + (cell.cast<double>() + Eigen::Vector2d::Constant(0.5)) * 0.05;
  EXPECT_NEAR(CorrelativeScore(t, {Eigen::Vector2d::Zero()}, SE2(p.x(), p.y(), 0.7)),
              std::exp(-(centre - p).squaredNorm() / (2 * 0.05 * 0.05)), 1e-6);
  EXPECT_EQ(CorrelativeScore(t, {Eigen::Vector2d::Zero()}, SE2(p.x() + 1.0, p.y(), 0)), 0.0);
  EXPECT_EQ(t.At(0, -1, 0), 0.0f);
  EXPECT_EQ(t.At(0, t.width, 0), 0.0f);
}

TEST(ScoreTable, PooledLevelsAreWindowMaxima) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Vector2d> map;
  for (int i = 0; i < 40; ++i) map.emplace_back(u(rng), u(rng));
  const ScoreTable t = MakeScoreTable(map, {.resolution_m = 0.05, .sigma_m = 0.04, .levels = 4});
  ExpectPooledLevelsAreWindowMaxima(t);
}

// With unknown_score u, a cell no ray crossed (behind a wall, beyond the table) scores u, a
// cell a ray crossed (free space) 0, a cell at a point the closed form as before; pooled levels
// stay the maxima over their windows, also across the table's edge.
TEST(ScoreTable, UnobservedCellsScoreTheUnknownValue) {
  std::vector<Eigen::Vector2d> wall, viewpoints;
  for (double y = -1.0; y <= 1.0; y += 0.02) {  // the wall x = 2, seen from the origin
    wall.emplace_back(2.0, y);
    viewpoints.emplace_back(0.0, 0.0);
  }
  const ScoreTableConfig c{.resolution_m = 0.05, .sigma_m = 0.05, .levels = 4, .unknown_score = 0.3};
  const ScoreTable t = MakeScoreTable(wall, c, viewpoints);
  const auto value = [&](double x, double y) { return CorrelativeScore(t, {Eigen::Vector2d(x, y)}, SE2()); };
  EXPECT_EQ(value(1.7, 0.0), 0.0);                   // in front of the wall: seen free
  EXPECT_NEAR(value(2.6, 0.0), 0.3, 1e-7);           // behind it: never seen
  EXPECT_NEAR(value(1.7, 1.2), 0.3, 1e-7);           // outside every ray's fan
  EXPECT_NEAR(value(40.0, 0.0), 0.3, 1e-7);          // beyond the table
  EXPECT_GT(value(2.0, 0.0), 0.3);                   // on the wall
  const ScoreTable free_as_before = MakeScoreTable(wall, {.resolution_m = 0.05, .sigma_m = 0.05, .levels = 4});
  EXPECT_EQ(CorrelativeScore(free_as_before, {Eigen::Vector2d(2.6, 0.0)}, SE2()), 0.0);
  ExpectPooledLevelsAreWindowMaxima(t);
  EXPECT_THROW(MakeScoreTable(wall, c), std::invalid_argument);  // no viewpoints
}

TEST(CorrelativeMatcher, BranchAndBoundEqualsExhaustiveOnRandomMaps) {
  for (std::uint64_t seed = 0; seed < 8; ++seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-3.0, 3.0), v(-0.3, 0.3);
    std::vector<Eigen::Vector2d> map, source;
    for (int i = 0; i < 150; ++i) map.emplace_back(u(rng), u(rng));
    for (int i = 0; i < 60; ++i) source.emplace_back(u(rng) * 0.5, u(rng) * 0.5);
    // Odd seeds: cells the map's rays (from the origin) never crossed score 0.2.
    std::vector<Eigen::Vector2d> viewpoints(map.size(), Eigen::Vector2d::Zero());
    const ScoreTable t = MakeScoreTable(
        map, {.resolution_m = 0.1, .sigma_m = 0.1, .levels = 4, .unknown_score = seed % 2 ? 0.2 : 0.0}, viewpoints);
    const SE2 guess(v(rng), v(rng), v(rng));
    const CorrelativeSearchConfig c{
        .linear_window_m = 1.0, .angular_window_deg = 10.0, .angular_step_deg = 2.5, .runner_up_radius_m = 0.3};
    const CorrelativeMatch bb = MatchCorrelative(t, source, guess, c);
    const CorrelativeMatch ex = MatchCorrelativeExhaustive(t, source, guess, c);
    ASSERT_TRUE(ex.found);
    ASSERT_TRUE(bb.found);
    EXPECT_EQ(bb.score, ex.score) << "seed " << seed;
    EXPECT_EQ(bb.runner_up_score, ex.runner_up_score) << "seed " << seed;
    EXPECT_GT(bb.runner_up_score, 0.0);
    EXPECT_LE(bb.runner_up_score, bb.score);
    // Its pose scores what it claims (the lattice pose rescored from scratch).
    EXPECT_NEAR(CorrelativeScore(t, source, bb.T_map_source), bb.score, 1e-9) << "seed " << seed;
  }
}

// In a featureless corridor every shift along it scores alike: the runner-up far from the
// best scores nearly as much. In a room it does not.
TEST(CorrelativeMatcher, RunnerUpExposesCorridorAmbiguity) {
  std::mt19937_64 rng(4);
  const CorrelativeSearchConfig c{.linear_window_m = 1.5, .angular_window_deg = 5, .runner_up_radius_m = 0.5};
  const auto ratio = [&](const std::vector<Segment>& walls, const SE2& A, const SE2& T) {
    const LaserScanEvent a = testing::RayCastScan(walls, A, 360, 0.01, rng);
    const LaserScanEvent b = testing::RayCastScan(walls, A * T, 360, 0.01, rng);
    const ScoreTable t = MakeScoreTable(ScanToPoints(a).points, {});
    const CorrelativeMatch m = MatchCorrelative(t, ScanToPoints(b).points, SE2(), c);
    EXPECT_TRUE(m.found);
    return m.runner_up_score / m.score;
  };
  EXPECT_GT(ratio(testing::CorridorWalls(), SE2(0, 0, 0), SE2(0.3, 0.05, 0.02)), 0.9);
  EXPECT_LT(ratio(testing::RoomWalls(), SE2(-1, -0.5, 0), SE2(0.3, 0.05, 0.02)), 0.8);
}

// The window is meant to hold the true pose. When it does, the optimum lies inside it; when
// the truth lies beyond it (a window drawn too small), the best the window holds sits on its
// boundary, where the score still rises outwards.
TEST(CorrelativeMatcher, FlagsAnOptimumOnTheWindowEdge) {
  std::mt19937_64 rng(7);
  const auto walls = testing::RoomWalls();
  const SE2 A(-1, -0.5, 0), T(0.6, -0.2, 4 * M_PI / 180);
  const LaserScanEvent a = testing::RayCastScan(walls, A, 360, 0.01, rng);
  const LaserScanEvent b = testing::RayCastScan(walls, A * T, 360, 0.01, rng);
  const ScoreTable t = MakeScoreTable(ScanToPoints(a).points, {});
  const std::vector<Eigen::Vector2d> source = ScanToPoints(b).points;
  const auto match = [&](double window_m, double window_deg) {
    return MatchCorrelative(t, source, SE2(), {.linear_window_m = window_m, .angular_window_deg = window_deg});
  };
  const CorrelativeMatch inside = match(1.0, 8);
  ASSERT_TRUE(inside.found);
  EXPECT_FALSE(inside.at_window_edge);
  EXPECT_NEAR(inside.T_map_source.x, T.x, 0.06);
  EXPECT_NEAR(inside.T_map_source.y, T.y, 0.06);
  const CorrelativeMatch short_x = match(0.3, 8);  // the truth is 0.6 m away in x
  ASSERT_TRUE(short_x.found);
  EXPECT_TRUE(short_x.at_window_edge);
  EXPECT_NEAR(short_x.T_map_source.x, 0.3, 1e-9);
  const CorrelativeMatch short_theta = match(1.0, 1.5);  // ... and 4 deg away in heading
  ASSERT_TRUE(short_theta.found);
  EXPECT_TRUE(short_theta.at_window_edge);
  EXPECT_FALSE(MatchCorrelative(t, {{50, 50}}, SE2(), {.linear_window_m = 0.3, .min_score = 0.1}).at_window_edge);
}

TEST(CorrelativeMatcher, MinScorePrunesEverything) {
  const ScoreTable t = MakeScoreTable({{0, 0}, {1, 0}}, {});
  const CorrelativeMatch m = MatchCorrelative(t, {{5, 5}}, SE2(), {.linear_window_m = 0.2, .min_score = 0.1});
  EXPECT_FALSE(m.found);
}

TEST(CorrelativeMatcher, FindsTwoMetreThirtyDegreeOffsetWhereIcpFails) {
  const auto walls = testing::RoomWalls();
  struct Case {
    SE2 A, T;
  };
  const Case cases[] = {{SE2(1.8, 1.8, 0.2), SE2(-2.0, -1.6, 30 * M_PI / 180)},
                        {SE2(2.0, -1.2, 0.0), SE2(-2.0, 1.0, -30 * M_PI / 180)},
                        {SE2(-1.0, 1.5, -0.3), SE2(1.6, -1.9, 25 * M_PI / 180)}};
  int icp_failures = 0;
  for (size_t i = 0; i < std::size(cases); ++i) {
    std::mt19937_64 rng(10 + i);
    const LaserScanEvent a = testing::RayCastScan(walls, cases[i].A, 360, 0.01, rng);
    const LaserScanEvent b = testing::RayCastScan(walls, cases[i].A * cases[i].T, 360, 0.01, rng);
    const ScanPoints pa = ScanToPoints(a), pb = ScanToPoints(b);
    const ScoreTable t = MakeScoreTable(pa.points, {.resolution_m = 0.05, .sigma_m = 0.05, .levels = 5});
    const CorrelativeMatch m = MatchCorrelative(t, pb.points, SE2(), {.linear_window_m = 2.2, .angular_window_deg = 32});
    ASSERT_TRUE(m.found);
    EXPECT_GT(m.score, 0.5);
    EXPECT_NEAR(m.T_map_source.x, cases[i].T.x, 0.06) << "case " << i;
    EXPECT_NEAR(m.T_map_source.y, cases[i].T.y, 0.06) << "case " << i;
    EXPECT_NEAR(NormalizeAngle(m.T_map_source.theta - cases[i].T.theta), 0.0, 1.0 * M_PI / 180) << "case " << i;
    // ICP from the zero guess (kd-tree, the loop-closure configuration) does not get there.
    const IcpTarget target = MakeScanTarget(pa, a);
    const IcpConfig icp{.correspondence = IcpCorrespondence::kKdTree, .max_iterations = 50, .max_correspondence_m = 0.5};
    const IcpResult r0 = RegisterIcp(pb.points, target, SE2(), icp);
    const bool icp_ok = (r0.T_target_source.translation() - cases[i].T.translation()).norm() < 0.1;
    EXPECT_FALSE(icp_ok) << "case " << i << ": ICP from zero reached " << r0.T_target_source.x << " "
                         << r0.T_target_source.y << " " << r0.T_target_source.theta;
    icp_failures += icp_ok ? 0 : 1;
    // ICP from the correlative match ends where ICP from the true offset ends (the pair's
    // own ICP optimum: a few cm from the truth with this little overlap).
    const IcpResult r = RegisterIcp(pb.points, target, m.T_map_source, icp);
    const IcpResult best = RegisterIcp(pb.points, target, cases[i].T, icp);
    EXPECT_NEAR(r.T_target_source.x, best.T_target_source.x, 1e-3) << "case " << i;
    EXPECT_NEAR(r.T_target_source.y, best.T_target_source.y, 1e-3) << "case " << i;
    EXPECT_NEAR(NormalizeAngle(r.T_target_source.theta - best.T_target_source.theta), 0.0, 1e-3);
    EXPECT_LT((r.T_target_source.translation() - cases[i].T.translation()).norm(), 0.05) << "case " << i;
    std::printf("case %zu: correlative %.3f %.3f %.2f deg, score %.3f, %d scores\n", i, m.T_map_source.x,
                m.T_map_source.y, m.T_map_source.theta * 180 / M_PI, m.score, m.evaluated);
  }
  EXPECT_EQ(icp_failures, static_cast<int>(std::size(cases)));
}

}  // namespace
}  // namespace slambox
