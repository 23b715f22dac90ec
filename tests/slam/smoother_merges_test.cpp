// Joint merges under the smoother's marginals (slam/smoother_merges.hpp) and the split of
// landmarks at re-observations after leaving view (slam/reobservation_split.hpp), on
// hand-built Gaussians and graphs whose answers follow by hand.
#include "slam/smoother_merges.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "slam/range_bearing.hpp"
#include "slam/reobservation_split.hpp"

namespace slambox {
namespace {

constexpr double kGate = 9.21;  // chi2(2) at 0.99
constexpr double kFake = 0.01;

TEST(MapDensity, LandmarksOverTheirConvexHull) {
  // A 2 x 1 rectangle's corners, its centre and a point on an edge: 6 over area 2.
  const Eigen::VectorXd m = (Eigen::VectorXd(12) << 0, 0, 2, 0, 2, 1, 0, 1, 1, 0.5, 1, 0).finished();
  EXPECT_NEAR(MapDensity(m), 3.0, 1e-12);
  EXPECT_EQ(MapDensity(Eigen::Vector4d(0, 0, 1, 1)), 0.0);  // fewer than 3: no area
}

/// Two landmarks (keys 1 and 2) with independent isotropic covariances s2 each, b at (d, 0)
/// from a: the difference has covariance 2 s2 I, so d^2 = d^2 / (2 s2) and mu = density pi
/// gate 2 s2.
JointLandmarks Pair(double d, double s2) {
  JointLandmarks L;
  L.keys = {1, 2};
  L.mean = Eigen::Vector4d(0, 0, d, 0);
  L.covariance = s2 * Eigen::Matrix4d::Identity();
  return L;
}

TEST(PairsDifferenceChi2, OnePairIsItsMahalanobisDistanceAndTwoPairsShareTheirCorrelation) {
  // One pair, independent sigma^2 = 0.01 each: d^2 = |b - a|^2 / 0.02.
  EXPECT_NEAR(PairsDifferenceChi2(Pair(0.3, 0.01), {{1, 2}}), 0.09 / 0.02, 1e-12);
  // Keys 1..4: a = (0, 0), b = (0.2, 0), c = (5, 0), e = (5, 0.1), sigma^2 = 0.01 each, and
  // b and e (the two removed) correlated 0.008 in x and y: D = (-0.2, 0, 0, -0.1), its
  // covariance [0.02 I, 0.008 I; 0.008 I, 0.02 I]. By hand, per axis the 2 x 2 block
  // [0.02 0.008; 0.008 0.02] has inverse [0.02 -0.008; -0.008 0.02] / 3.36e-4:
  // x: (-0.2)^2 0.02 / 3.36e-4; y: (-0.1)^2 0.02 / 3.36e-4.
  JointLandmarks L;
  L.keys = {1, 2, 3, 4};
  L.mean = (Eigen::VectorXd(8) << 0, 0, 0.2, 0, 5, 0, 5, 0.1).finished();
  L.covariance = 0.01 * Eigen::MatrixXd::Identity(8, 8);
  L.covariance.block<2, 2>(2, 6) = L.covariance.block<2, 2>(6, 2) = 0.008 * Eigen::Matrix2d::Identity();
  const double by_hand = (0.04 * 0.02 + 0.01 * 0.02) / 3.36e-4;
  EXPECT_NEAR(PairsDifferenceChi2(L, {{1, 2}, {3, 4}}), by_hand, 1e-9);
  // Each alone ignores the other's correlation: 0.04 / 0.02 and 0.01 / 0.02, summing to less.
  EXPECT_NEAR(PairsDifferenceChi2(L, {{1, 2}}) + PairsDifferenceChi2(L, {{3, 4}}), 2.5, 1e-9);
  // Perfectly correlated landmarks: their difference has no covariance.
  JointLandmarks same = Pair(0.3, 0.01);
  same.covariance.setConstant(0.0);
  same.covariance.diagonal().setConstant(0.01);
  same.covariance.block<2, 2>(0, 2) = same.covariance.block<2, 2>(2, 0) = 0.01 * Eigen::Matrix2d::Identity();
  EXPECT_TRUE(std::isinf(PairsDifferenceChi2(same, {{1, 2}})));
}

TEST(FindJointMerges, OnePairAtTheGateAndAtTheFakeThreshold) {
  const double s2 = 0.01;  // sigma 0.1 m each: C = 0.02 I
  const double density = 0.5 * kFake / (M_PI * kGate * 2 * s2);  // mu = 0.005
  const MergeSearchSettings s{kGate, kFake, density};
  const double d_gate = std::sqrt(kGate * 2 * s2);
  EXPECT_EQ(FindJointMerges(Pair(0.99 * d_gate, s2), {}, s), (std::vector<std::pair<int, int>>{{1, 2}}));
  EXPECT_TRUE(FindJointMerges(Pair(1.01 * d_gate, s2), {}, s).empty());
  // Twice the density: mu = 0.02 > 0.01, a lone pair is not evidence enough.
  EXPECT_TRUE(FindJointMerges(Pair(0.5 * d_gate, s2), {}, {kGate, kFake, 4 * density}).empty());
}

TEST(FindJointMerges, NeverMergesTwoLandmarksSeenInOneScan) {
  // Two trees 0.3 m apart, closer than a 1-sigma gate: seen together, they stay two.
  const MergeSearchSettings s{kGate, kFake, 1e-6};
  EXPECT_EQ(FindJointMerges(Pair(0.3, 0.04), {}, s).size(), 1u);
  EXPECT_TRUE(FindJointMerges(Pair(0.3, 0.04), {{1, 2}}, s).empty());
}

TEST(UnchallengedPairings, KeepsTheFrontEndsPairingUnlessRejectedOrRivalled) {
  const double s2 = 0.01;  // C = 0.02 I: d^2 = d^2 / 0.02
  const double keep = 25.0;
  const auto d_at = [&](double chi2) { return std::sqrt(chi2 * 2 * s2); };
  const std::vector<std::pair<int, int>> proposal = {{2, 1}};  // segment 2, paired with 1
  // Outside the merge gate, inside the front end's rejection gate: kept.
  EXPECT_EQ(UnchallengedPairings(Pair(d_at(15.0), s2), {}, proposal, kGate, keep),
            (std::vector<std::pair<int, int>>{{1, 2}}));
  EXPECT_TRUE(UnchallengedPairings(Pair(d_at(26.0), s2), {}, proposal, kGate, keep).empty());  // rejected
  // Only proposals are kept: two landmarks close by but never paired stay two.
  EXPECT_TRUE(UnchallengedPairings(Pair(d_at(1.0), s2), {}, {}, kGate, keep).empty());
  EXPECT_TRUE(UnchallengedPairings(Pair(d_at(1.0), s2), {{1, 2}}, proposal, kGate, keep).empty());  // seen together
  // A third landmark (key 3) inside the segment's gate (d^2 8), outside 1's (14.7), rivals
  // the pairing.
  JointLandmarks L;
  L.keys = {1, 2, 3};
  L.mean = (Eigen::VectorXd(6) << 0, 0, d_at(1.0), 0, d_at(1.0) + d_at(8.0), 0).finished();
  L.covariance = s2 * Eigen::MatrixXd::Identity(6, 6);
  EXPECT_TRUE(UnchallengedPairings(L, {}, proposal, kGate, keep).empty());
  // ... unless it was seen with the segment: then it is another landmark, not a rival.
  EXPECT_EQ(UnchallengedPairings(L, {{2, 3}}, proposal, kGate, keep), (std::vector<std::pair<int, int>>{{1, 2}}));
}

/// Lap 1: trees p_i (keys 0..n-1, sigma 0.05 m); lap 2: the same trees mapped again
/// (keys 100..) shifted by one common unknown offset (sigma `offset_sigma_m`) plus
/// 0.05 m of their own. Offset (1.5, -1.0) m in the mean.
JointLandmarks TwoLaps(const std::vector<Eigen::Vector2d>& p, double offset_sigma_m) {
  const int n = static_cast<int>(p.size());
  JointLandmarks L;
  L.mean.resize(4 * n);
  L.covariance = 0.0025 * Eigen::MatrixXd::Identity(4 * n, 4 * n);
  for (int i = 0; i < n; ++i) {
    L.keys.push_back(i);
    L.mean.segment<2>(2 * i) = p[i];
  }
  for (int i = 0; i < n; ++i) {
    L.keys.push_back(100 + i);
    L.mean.segment<2>(2 * (n + i)) = p[i] + Eigen::Vector2d(1.5, -1.0);
    for (int j = 0; j < n; ++j)
      L.covariance.block<2, 2>(2 * (n + i), 2 * (n + j)) += std::pow(offset_sigma_m, 2) * Eigen::Matrix2d::Identity();
  }
  return L;
}

const std::vector<Eigen::Vector2d> kTrees = {{0, 0}, {4.1, 0.7}, {1.3, 5.2}, {6.8, 4.4}, {3.2, 9.1}, {8.9, 8.3}};

TEST(FindJointMerges, ADuplicatedLapMergesJointlyWhereNoPairAloneWould) {
  const JointLandmarks L = TwoLaps(kTrees, 2.0);  // each pair alone: C about 8 I, gate radius 8.6 m
  const MergeSearchSettings s{kGate, kFake, 6.0 / 80.0};
  // Alone, the first pair expects mu = density pi gate sqrt(det C) = 0.075 * 9.21 pi 8 = 17 other trees in its gate.
  const std::vector<std::pair<int, int>> merges = FindJointMerges(L, {}, s);
  ASSERT_EQ(merges.size(), kTrees.size());
  for (size_t i = 0; i < kTrees.size(); ++i) EXPECT_EQ(merges[i], std::make_pair(static_cast<int>(i), 100 + static_cast<int>(i)));
  // A second lap of one tree alone cannot be told from a shifted neighbour: no merge.
  const JointLandmarks one = TwoLaps({kTrees[0], kTrees[1], kTrees[2]}, 2.0);
  JointLandmarks lone;
  lone.keys = {0, 1, 2, 100};
  lone.mean = one.mean.head(8);
  lone.covariance = one.covariance.topLeftCorner(8, 8);
  EXPECT_TRUE(FindJointMerges(lone, {}, s).empty());
}

TEST(FindJointMerges, LeavesOutAPairTheHypothesisExplainsWorseThanTwoLandmarks) {
  // The duplicated lap, plus a lap-1 landmark (key 6) and a lap-2 one (key 106) at the ends
  // of their laps' open chains, sigma 1.1 m each and independent of the rest: 3.5 m apart,
  // C = 2.42 I, d^2 = 5.06 < gate, so every hypothesis can take them as a seventh pair. Its
  // gate expects mu = 0.075 pi 9.21 2.42 = 5.3 other trees: no evidence against the
  // hypothesis either way (min(1, mu) = 1), so by size it would be taken; as a likelihood
  // factor it is exp(-5.06 / 2) 9.21 / (2 mu) = 0.07 < 1 (seed 121 of `forest` had such a
  // pair: 29 pairs, this one wrong, d^2 5.5, mu 0.7).
  JointLandmarks six = TwoLaps(kTrees, 2.0);
  const int n = static_cast<int>(six.keys.size());
  JointLandmarks L;
  L.keys = six.keys;
  L.keys.insert(L.keys.begin() + n / 2, 6);
  L.keys.push_back(106);
  L.mean.resize(2 * (n + 2));
  L.covariance = Eigen::MatrixXd::Zero(2 * (n + 2), 2 * (n + 2));
  const std::vector<int> from = {0, 1, 2, 3, 4, 5, -1, 6, 7, 8, 9, 10, 11, -1};  // index in `six`, -1: new
  for (int i = 0; i < n + 2; ++i) {
    if (from[i] < 0) {
      L.mean.segment<2>(2 * i) = i < n / 2 + 1 ? Eigen::Vector2d(20.0, 0.0) : Eigen::Vector2d(23.5, 0.0);
      L.covariance.block<2, 2>(2 * i, 2 * i) = 1.21 * Eigen::Matrix2d::Identity();
      continue;
    }
    L.mean.segment<2>(2 * i) = six.mean.segment<2>(2 * from[i]);
    for (int j = 0; j < n + 2; ++j)
      if (from[j] >= 0) L.covariance.block<2, 2>(2 * i, 2 * j) = six.covariance.block<2, 2>(2 * from[i], 2 * from[j]);
  }
  const MergeSearchSettings s{kGate, kFake, 6.0 / 80.0};
  std::vector<std::pair<int, int>> expected;
  for (int i = 0; i < 6; ++i) expected.emplace_back(i, 100 + i);
  EXPECT_EQ(FindJointMerges(L, {}, s), expected);
  // Twenty times sparser (mu 0.27), the same pair is more likely one landmark than two.
  expected.emplace_back(6, 106);
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(FindJointMerges(L, {}, {kGate, kFake, 6.0 / 80.0 / 20.0}), expected);
}

/// Robot poses along x at 0.2 m spacing (heading 0 unless changed), a 180 deg, 5 m
/// detector, odometry between them with covariance sigma^2 I; one landmark at (2, 1).
/// `observed`: the keyframes that observe it.
LandmarkGraph Corridor(const std::vector<SE2>& poses, const std::vector<int>& observed, double odometry_sigma) {
  LandmarkGraph g;
  g.poses = poses;
  for (size_t k = 0; k + 1 < poses.size(); ++k)
    g.odometry.push_back({static_cast<int>(k), poses[k].inverse() * poses[k + 1],
                          std::pow(odometry_sigma, 2) * Eigen::Matrix3d::Identity()});
  g.observation_covariance = Eigen::Vector2d(0.01, std::pow(M_PI / 180, 2)).asDiagonal();
  g.landmarks[7] = Eigen::Vector2d(2, 1);
  for (const int k : observed) g.observations.push_back({k, 7, PredictObservation(poses[k], g.landmarks[7]).z});
  return g;
}

TEST(SplitAtReobservations, SplitsOnlyWhereTheLandmarkLeftViewAndDeadReckoningIsAmbiguous) {
  const SensorFootprint footprint{5.0, M_PI / 2};
  const MergeSearchSettings test{kGate, kFake, 0.05};  // a landmark per 20 m^2
  std::vector<SE2> poses;
  for (int k = 0; k < 8; ++k) poses.emplace_back(0.2 * k, 0.0, 0.0);
  // Missed at keyframes 2..4 while in view (a missed detection): one segment.
  LandmarkGraph in_view = Corridor(poses, {0, 1, 5, 6}, 1.0);
  EXPECT_TRUE(SplitAtReobservations(in_view, footprint, test, 50).segments.empty());
  for (const auto& o : in_view.observations) EXPECT_EQ(o.landmark, 7);
  // The robot turned away at keyframe 3 (the landmark behind it): a new segment from 5.
  poses[3].theta = M_PI;
  LandmarkGraph turned = Corridor(poses, {0, 1, 5, 6}, 1.0);
  const ReobservationSplit split = SplitAtReobservations(turned, footprint, test, 50);
  ASSERT_EQ(split.segments.at(7).size(), 1u);
  EXPECT_EQ(split.segments.at(7)[0].first_keyframe, 5);
  EXPECT_EQ(split.segments.at(7)[0].key, 50);
  EXPECT_EQ(turned.observations[1].landmark, 7);
  EXPECT_EQ(turned.observations[2].landmark, 50);
  EXPECT_EQ(turned.observations[3].landmark, 50);
  EXPECT_NEAR((split.guesses.at(50) - Eigen::Vector2d(2, 1)).norm(), 0.0, 1e-12);  // exact observations
  EXPECT_EQ(SegmentKey(split, 7, 4), 7);
  EXPECT_EQ(SegmentKey(split, 7, 5), 50);
  EXPECT_EQ(SegmentKey(split, 3, 5), 3);  // a landmark never split
  // The same turn with odometry of 1 mm / 1 mrad: the re-observation cannot be ambiguous.
  LandmarkGraph certain = Corridor(poses, {0, 1, 5, 6}, 1e-3);
  EXPECT_LT(ReobservationAmbiguity(certain, 1, 5, Eigen::Vector2d(2, 1), certain.observations[2].z, test), kFake);
  EXPECT_TRUE(SplitAtReobservations(certain, footprint, test, 50).segments.empty());
  // Out of range instead of out of view: the same.
  poses[3] = SE2(-10.0, 0.0, 0.0);
  LandmarkGraph far = Corridor(poses, {0, 1, 5, 6}, 1.0);
  EXPECT_EQ(SplitAtReobservations(far, footprint, test, 50).segments.size(), 1u);
}

TEST(ReobservationAmbiguity, ClosedFormForATranslationOnlyChain) {
  // One odometry step of covariance diag(a, b, 0) straight ahead, landmark straight ahead at
  // range r and bearing 0: J Sigma J^T = diag(a, b), G R G^T = diag(sr^2, r^2 sb^2).
  LandmarkGraph g;
  g.poses = {SE2(0, 0, 0), SE2(1, 0, 0)};
  g.odometry.push_back({0, SE2(1, 0, 0), Eigen::Vector3d(0.04, 0.09, 0.0).asDiagonal()});
  g.observation_covariance = Eigen::Vector2d(0.01, 0.0004).asDiagonal();
  const MergeSearchSettings test{kGate, kFake, 0.1};
  const double r = 4.0;
  const double det = (0.04 + 2 * 0.01) * (0.09 + 2 * r * r * 0.0004);
  EXPECT_NEAR(ReobservationAmbiguity(g, 0, 1, Eigen::Vector2d(1 + r, 0), Eigen::Vector2d(r, 0), test),
              0.1 * M_PI * kGate * std::sqrt(det), 1e-12);
}

}  // namespace
}  // namespace slambox
