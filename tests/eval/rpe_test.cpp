#include "eval/rpe.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace slambox {
namespace {

std::vector<SE2> AlongX(const std::vector<double>& x) {
  std::vector<SE2> p;
  for (double v : x) p.emplace_back(v, 0.0, 0.0);
  return p;
}

std::vector<SE2> Headings(const std::vector<double>& deg) {
  std::vector<SE2> p;
  for (double d : deg) p.emplace_back(0.0, 0.0, d * M_PI / 180);
  return p;
}

using Pairs = std::vector<IndexPair>;

TEST(RpePairs, FramesConsecutiveAndAllPairs) {
  const auto poses = AlongX(std::vector<double>(10, 0.0));
  EXPECT_EQ(SelectPairs(poses, {.delta = 3, .unit = DeltaUnit::kFrames}), (Pairs{{0, 3}, {3, 6}, {6, 9}}));
  const Pairs all = SelectPairs(poses, {.delta = 3, .unit = DeltaUnit::kFrames, .all_pairs = true});
  ASSERT_EQ(all.size(), 7u);
  EXPECT_EQ(all.front(), IndexPair(0, 3));
  EXPECT_EQ(all.back(), IndexPair(6, 9));
}

TEST(RpePairs, MetresConsecutiveStartAfterTheFirstDelta) {
  // evo accumulates path from pose 0 and records an index each time the sum reaches delta:
  // the first recorded index is 2 (1.0 m), so the first pair is (2, 4), not (0, 2).
  const auto poses = AlongX({0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0});
  EXPECT_EQ(SelectPairs(poses, {.delta = 1.0}), (Pairs{{2, 4}, {4, 6}}));
  // The sum restarts at 0 after each record: 0.4-m steps record at 1.2, 2.4 (3 steps each).
  const auto coarse = AlongX({0.0, 0.4, 0.8, 1.2, 1.6, 2.0, 2.4, 2.8, 3.2, 3.6});
  EXPECT_EQ(SelectPairs(coarse, {.delta = 1.0}), (Pairs{{3, 6}, {6, 9}}));
}

TEST(RpePairs, MetresAllPairsWithTenPercentTolerance) {
  // Path distances from each i: the j nearest to 1 m is kept if within 0.1 m.
  // (Dyadic values: the arithmetic is exact.)
  const auto poses = AlongX({0.0, 0.5, 0.9375, 1.25, 2.0, 2.5});
  // i=0: 0.9375 (err .0625) -> (0,2). i=1: 0.75 (err .25): none. i=2: 1.0625 -> (2,4).
  // i=3: 0.75 and 1.25 (both err .25): none. i=4: 0.5: none.
  EXPECT_EQ(SelectPairs(poses, {.delta = 1.0, .all_pairs = true}), (Pairs{{0, 2}, {2, 4}}));
  // A wider tolerance admits (1,3) and, for i=3's tie, the first index (argmin): (3,4).
  const Pairs wide = SelectPairs(poses, {.delta = 1.0, .all_pairs = true, .rel_delta_tol = 0.3});
  EXPECT_EQ(wide, (Pairs{{0, 2}, {1, 3}, {2, 4}, {3, 4}}));
}

TEST(RpePairs, MetresUseTravelledPathNotDirectDistance) {
  // Out and back: direct distance from 0 to 4 is 0, path is 2 m.
  const auto poses = AlongX({0.0, 0.5, 1.0, 0.5, 0.0});
  EXPECT_EQ(SelectPairs(poses, {.delta = 2.0, .all_pairs = true}), (Pairs{{0, 4}}));
}

TEST(RpePairs, DegreesConsecutiveAndAllPairs) {
  const auto turning = Headings({0, 10, 20, 30, 40, 50, 60, 70});
  EXPECT_EQ(SelectPairs(turning, {.delta = 25, .unit = DeltaUnit::kDegrees}), (Pairs{{0, 3}, {3, 6}}));
  const auto h = Headings({0, 30, 45, 75, 100});
  // Direct relative angle in [40.5, 49.5] deg: (0,2) 45 and (1,3) 45.
  EXPECT_EQ(SelectPairs(h, {.delta = 45, .unit = DeltaUnit::kDegrees, .all_pairs = true}), (Pairs{{0, 2}, {1, 3}}));
  // Across the +-180 wrap: 170 -> -170 is a 20 deg turn (not 340).
  const auto wrap = Headings({170, -170, -150});
  EXPECT_EQ(SelectPairs(wrap, {.delta = 19, .unit = DeltaUnit::kDegrees}), (Pairs{{0, 1}, {1, 2}}));
}

TEST(Rpe, HandComputedError) {
  // Q: identity -> (1, 0, 0); P: identity -> (1.1, 0.1, 0.1 rad): E = (0.1, 0.1, 0.1 rad).
  const SE2 E = RelativePoseError(SE2(), SE2(1, 0, 0), SE2(), SE2(1.1, 0.1, 0.1));
  EXPECT_NEAR(E.x, 0.1, 1e-15);
  EXPECT_NEAR(E.y, 0.1, 1e-15);
  EXPECT_NEAR(E.theta, 0.1, 1e-15);
  const RpeResult r = ComputeRpe({SE2(), SE2(1, 0, 0)}, {SE2(), SE2(1.1, 0.1, 0.1)},
                                 {.delta = 1, .unit = DeltaUnit::kFrames});
  ASSERT_EQ(r.translation_m.size(), 1u);
  EXPECT_NEAR(r.translation_m[0], std::sqrt(0.02), 1e-15);
  EXPECT_NEAR(r.rotation_deg[0], 0.1 * 180 / M_PI, 1e-12);
}

TEST(Rpe, EqualsTheCompositionDefinition) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-5, 5);
  for (int k = 0; k < 200; ++k) {
    const SE2 Qi(u(rng), u(rng), u(rng)), Qj(u(rng), u(rng), u(rng)), Pi(u(rng), u(rng), u(rng)),
        Pj(u(rng), u(rng), u(rng));
    const SE2 expected = (Qi.inverse() * Qj).inverse() * (Pi.inverse() * Pj);
    const SE2 E = RelativePoseError(Qi, Qj, Pi, Pj);
    EXPECT_NEAR(E.x, expected.x, 1e-12);
    EXPECT_NEAR(E.y, expected.y, 1e-12);
    EXPECT_NEAR(NormalizeAngle(E.theta - expected.theta), 0.0, 1e-12);
  }
}

TEST(Rpe, IdenticalTrajectoriesGiveExactlyZero) {
  std::vector<SE2> path;
  for (int i = 0; i < 200; ++i) path.emplace_back(0.1 * i * std::cos(0.05 * i), 0.2 * i, M_PI - 0.03 * i);
  path.emplace_back(5, 5, -M_PI);
  path.emplace_back(5.5, 5, M_PI - 1e-15);
  for (bool all : {false, true}) {
    const RpeResult r = ComputeRpe(path, path, {.delta = 1.0, .all_pairs = all});
    ASSERT_FALSE(r.pairs.empty());
    for (size_t k = 0; k < r.pairs.size(); ++k) {
      EXPECT_EQ(r.translation_m[k], 0.0);
      EXPECT_EQ(r.rotation_deg[k], 0.0);
    }
  }
}

TEST(Rpe, InvariantToAGlobalRigidTransformOfTheEstimate) {
  std::mt19937_64 rng(9);
  std::normal_distribution<double> n(0, 0.05);
  std::vector<SE2> gt, est, moved;
  const SE2 T(10, -3, 2.0);
  for (int i = 0; i < 100; ++i) {
    gt.emplace_back(0.3 * i, std::sin(0.1 * i), 0.1 * i);
    est.emplace_back(gt.back().x + n(rng), gt.back().y + n(rng), gt.back().theta + n(rng));
    moved.push_back(T * est.back());
  }
  const RpeResult a = ComputeRpe(gt, est, {}), b = ComputeRpe(gt, moved, {});
  ASSERT_EQ(a.pairs, b.pairs);
  for (size_t k = 0; k < a.pairs.size(); ++k) EXPECT_NEAR(a.translation_m[k], b.translation_m[k], 1e-9);
}

TEST(Rpe, PairsComeFromTheEstimateUnlessAskedForTheReference) {
  const auto gt = AlongX({0, 1, 2, 3, 4});
  const auto est = AlongX({0, 2, 4, 6, 8});  // twice as fast: 2 m per step
  EXPECT_EQ(ComputeRpe(gt, est, {.delta = 2.0}).pairs, (Pairs{{1, 2}, {2, 3}, {3, 4}}));
  EXPECT_EQ(ComputeRpe(gt, est, {.delta = 2.0, .pairs_from_reference = true}).pairs, (Pairs{{2, 4}}));
}

TEST(Rpe, ParsesDeltaUnits) {
  DeltaUnit u;
  EXPECT_TRUE(ParseDeltaUnit("m", u));
  EXPECT_EQ(u, DeltaUnit::kMeters);
  EXPECT_TRUE(ParseDeltaUnit("f", u));
  EXPECT_EQ(u, DeltaUnit::kFrames);
  EXPECT_TRUE(ParseDeltaUnit("d", u));
  EXPECT_EQ(u, DeltaUnit::kDegrees);
  EXPECT_FALSE(ParseDeltaUnit("rad", u));
}

}  // namespace
}  // namespace slambox
