// Region loop search (slam/loop_region.hpp): passes split at gaps; a pass placed where the
// estimate says is admitted, the same pass moved by 0.3 m or turned by 3 deg is not; and a
// region of two consistent passes, each of which saw a different half of a hall, matches a
// 360-deg scan of 30 m range from its middle where either pass alone does not reach the
// closure score.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "slam/correlative_matcher.hpp"
#include "slam/loop_region.hpp"
#include "slam/scan_points.hpp"
#include "tests/support/synthetic_scan.hpp"

namespace slambox {
namespace {

using testing::Polyline;
using testing::RayCastScan;

// A 20 m x 8 m hall with boxes and alcoves, so that a match is not ambiguous.
std::vector<Segment> Hall() {
  auto w = Polyline({{-10, -4}, {-2, -4}, {-2, -5}, {-1, -5}, {-1, -4}, {10, -4}, {10, 4}, {3, 4}, {3, 5}, {2, 5},
                     {2, 4}, {-10, 4}},
                    true);
  for (const Eigen::Vector2d& c : {Eigen::Vector2d(-6, 1.5), Eigen::Vector2d(-4, -2), Eigen::Vector2d(5, -1.5),
                                  Eigen::Vector2d(7, 2), Eigen::Vector2d(0.5, 2.5)}) {
    auto b = Polyline({c + Eigen::Vector2d(-0.3, -0.3), c + Eigen::Vector2d(0.3, -0.3), c + Eigen::Vector2d(0.3, 0.3),
                       c + Eigen::Vector2d(-0.3, 0.3)},
                      true);
    w.insert(w.end(), b.begin(), b.end());
  }
  return w;
}

// Points of a scan with a 180-deg field of view facing the pose's heading (robot frame).
std::vector<Eigen::Vector2d> FrontHalf(const LaserScanEvent& scan) {
  std::vector<Eigen::Vector2d> out;
  for (const auto& p : ScanToPoints(scan).points)
    if (p.x() > 0) out.push_back(p);
  return out;
}

struct TwoPasses {
  std::vector<SE2> truth;                          // keyframes 0..4: pass A, 10..14: pass B
  std::vector<std::vector<Eigen::Vector2d>> points;  // robot frame
};

// Pass A walks +x from x = -2 to 0 facing +x with an 8 m range (it sees -2 < x < 8); pass B
// walks -x from 2 to 0 facing -x (-8 < x < 2); they overlap on -2 < x < 2. Keyframes 5..9
// (between them) are not members.
TwoPasses MakePasses(std::mt19937_64& rng) {
  TwoPasses t;
  const auto walls = Hall();
  for (int i = 0; i < 15; ++i) {
    const SE2 pose = i < 10 ? SE2(-2.0 + 0.5 * i, 0.3, 0.0) : SE2(2.0 - 0.5 * (i - 10), -0.3, M_PI);
    t.truth.push_back(pose);
    t.points.push_back(FrontHalf(RayCastScan(walls, pose, 720, 0.01, rng, 8.0)));
  }
  return t;
}

std::vector<const std::vector<Eigen::Vector2d>*> Pointers(const TwoPasses& t) {
  std::vector<const std::vector<Eigen::Vector2d>*> p;
  for (const auto& v : t.points) p.push_back(&v);
  return p;
}

const std::vector<int> kMembers = {0, 1, 2, 3, 4, 10, 11, 12, 13, 14};

TEST(LoopRegion, SplitsMembersIntoPasses) {
  const auto p = SplitIntoPasses({2, 3, 4, 9, 11, 12});
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p[0].first, 2);
  EXPECT_EQ(p[0].last, 4);
  EXPECT_EQ(p[1].first, 9);
  EXPECT_EQ(p[1].last, 9);
  EXPECT_EQ(p[2].first, 11);
  EXPECT_EQ(p[2].last, 12);
}

TEST(LoopRegion, AdmitsConsistentPassesOnly) {
  std::mt19937_64 rng(7);
  const TwoPasses t = MakePasses(rng);
  const RegionConfig config;
  const RegionSelection ok = SelectConsistentPasses(t.truth, Pointers(t), kMembers, 2, Eigen::Vector2d(0, 0), config);
  ASSERT_EQ(ok.passes.size(), 2u);
  EXPECT_EQ(ok.admitted_passes, 2) << "agreement " << ok.agreement[1].score << " overlap " << ok.agreement[1].overlap
                                   << " / " << ok.agreement[1].points;
  EXPECT_EQ(ok.keyframes, kMembers);
  // Pass B placed 0.3 m off, or turned 3 deg about its middle, by the estimate: a doubled wall.
  for (const SE2& error : {SE2(0.0, 0.3, 0.0), SE2(0.0, 0.0, 3.0 * M_PI / 180)}) {
    std::vector<SE2> estimate = t.truth;
    const SE2 centre(0.0, -0.3, M_PI);
    for (int i = 10; i < 15; ++i) estimate[i] = centre * error * centre.inverse() * t.truth[i];
    const RegionSelection bad = SelectConsistentPasses(estimate, Pointers(t), kMembers, 2, Eigen::Vector2d(0, 0), config);
    EXPECT_EQ(bad.admitted_passes, 1) << "agreement " << bad.agreement[1].score;
    EXPECT_EQ(bad.keyframes, (std::vector<int>{0, 1, 2, 3, 4}));
  }
}

TEST(LoopRegion, TwoConsistentPassesMatchWhereOnePassDoesNot) {
  std::mt19937_64 rng(11);
  const TwoPasses t = MakePasses(rng);
  const SE2 query(0.2, 0.0, 0.5 * M_PI);
  const std::vector<Eigen::Vector2d> source = ScanToPoints(RayCastScan(Hall(), query, 720, 0.01, rng)).points;
  auto table_of = [&](const std::vector<int>& keyframes) {
    std::vector<Eigen::Vector2d> map;
    for (int i : keyframes)
      for (const auto& p : t.points[static_cast<size_t>(i)]) map.push_back(t.truth[static_cast<size_t>(i)] * p);
    return MakeScoreTable(map, {});
  };
  CorrelativeSearchConfig search;
  search.linear_window_m = 1.0;
  search.angular_window_deg = 10.0;
  const SE2 guess = query * SE2(0.6, -0.4, 4.0 * M_PI / 180);  // the estimate's error
  const RegionSelection region = SelectConsistentPasses(t.truth, Pointers(t), kMembers, 2, query.translation(), {});
  const CorrelativeMatch both = MatchCorrelative(table_of(region.keyframes), source, guess, search);
  const CorrelativeMatch a = MatchCorrelative(table_of({0, 1, 2, 3, 4}), source, guess, search);
  const CorrelativeMatch b = MatchCorrelative(table_of({10, 11, 12, 13, 14}), source, guess, search);
  const double closure_score = 0.6;  // icp-poseslam's loop_min_score
  EXPECT_GE(both.score, closure_score);
  EXPECT_LT(a.score, closure_score);
  EXPECT_LT(b.score, closure_score);
  EXPECT_LT((both.T_map_source.translation() - query.translation()).norm(), 0.1);
  EXPECT_LT(std::abs(NormalizeAngle(both.T_map_source.theta - query.theta)), 1.5 * M_PI / 180);
  std::printf("region score %.3f, pass A alone %.3f, pass B alone %.3f\n", both.score, a.score, b.score);
}

}  // namespace
}  // namespace slambox
