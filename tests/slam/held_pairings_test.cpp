// Held pairings (slam/held_pairings.hpp) against hand-computed fake probabilities: mu is
// the clutter density times the gate's area in the plane (pi chi2 sqrt(det S) r); a
// pairing is held while the product over its evidence is above the gate's miss
// probability 1 - P[chi2(2) < 9.21] = 0.01.
#include "slam/held_pairings.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>

#include "slam/data_association.hpp"

namespace slambox {
namespace {

constexpr double kGate = 9.21;

/// Robot at the origin (sigma 1 m in x and y, 0.1 rad), landmarks at (5, 0) and (0, 5)
/// (sigma 0.1 m), keys 10 and 20; range-bearing noise 0.1 m / 1 deg.
struct Scene {
  EkfSlamState state;
  Eigen::Matrix2d R = Eigen::Vector2d(0.01, std::pow(M_PI / 180, 2)).asDiagonal();
  std::vector<int> keys = {10, 20};
  mutable TrackEvidence tracks = {std::nullopt, std::nullopt};
  std::vector<Eigen::Vector2d> z = {{5, 0}, {5, M_PI / 2}};  // each landmark exactly where predicted
  Scene() {
    state.mean = (Eigen::VectorXd(7) << 0, 0, 0, 5, 0, 0, 5).finished();
    state.covariance = (Eigen::VectorXd(7) << 1, 1, 0.01, 0.01, 0.01, 0.01, 0.01).finished().asDiagonal();
  }
  /// The density that puts `mu` fakes into landmark j's gate.
  double DensityFor(double mu, int j) const {
    return mu / (M_PI * kGate * std::sqrt(InnovationCovariance(state, j, R).determinant()) * 5.0);
  }
  /// One scan that sees only landmark j; returns whether it was held.
  bool Scan(int j, const HoldTest& test, HeldStreak& streak) const {
    std::vector<int> target = {Association::kDiscard, Association::kDiscard};
    target[j] = j;
    const std::vector<bool> held = HoldUncertainPairings(state, z, R, keys, tracks, test, target, streak);
    EXPECT_EQ(target[j], held[j] ? Association::kDiscard : j);
    return held[j];
  }
};

TEST(HeldPairings, HeldExactlyWhileTheFakeProbabilityIsAboveTheGateMiss) {
  const Scene s;
  // Both landmarks' gates have the same area (the robot's covariance is isotropic in x, y).
  EXPECT_NEAR(s.DensityFor(1, 0), s.DensityFor(1, 1), 1e-12);
  for (const auto& [mu, held] : std::vector<std::pair<double, bool>>{{0.0105, true}, {0.0095, false}}) {
    HeldStreak streak;
    EXPECT_EQ(s.Scan(0, {kGate, s.DensityFor(mu, 0)}, streak), held) << mu;
    if (held) EXPECT_NEAR(streak.at(10), std::log(mu), 1e-9);
    else EXPECT_TRUE(streak.empty());
  }
}

TEST(HeldPairings, DistinctLandmarksMultiplyRepeatsDoNot) {
  const Scene s;
  const HoldTest test{kGate, s.DensityFor(0.05, 0), HoldEvidence::kDistinctLandmarks};
  HeldStreak streak;
  EXPECT_TRUE(s.Scan(0, test, streak));   // 0.05
  EXPECT_TRUE(s.Scan(0, test, streak));   // a repeat: still 0.05
  EXPECT_NEAR(streak.at(10), std::log(0.05), 1e-9);
  EXPECT_FALSE(s.Scan(1, test, streak));  // 0.05 * 0.05 = 0.0025 < 0.01: used
}

TEST(HeldPairings, RepeatedScansMultiplyRepeatsOnly) {
  const Scene s;
  const HoldTest test{kGate, s.DensityFor(0.05, 0), HoldEvidence::kRepeatedScans};
  HeldStreak streak;
  EXPECT_TRUE(s.Scan(0, test, streak));
  EXPECT_TRUE(s.Scan(1, test, streak));   // another landmark: its own streak, 0.05
  EXPECT_FALSE(streak.count(10));         // landmark 0's streak ended with a scan that did not hold it
  EXPECT_FALSE(s.Scan(1, test, streak));  // its repeat: 0.0025, used
}

TEST(HeldPairings, ATrackMultipliesItsHeldRepeatsUntilOneIsUsed) {
  Scene s;
  s.tracks = {0.0, std::nullopt};  // landmark 0's track has just started, landmark 1 has none
  const HoldTest test{kGate, s.DensityFor(0.05, 0), HoldEvidence::kLandmarksAndTracks};
  HeldStreak streak;
  EXPECT_TRUE(s.Scan(0, test, streak));   // 0.05
  EXPECT_NEAR(*s.tracks[0], std::log(0.05), 1e-9);
  EXPECT_FALSE(s.Scan(0, test, streak));  // its held repeat counts: 0.05^2 = 0.0025 < 0.01, used
  EXPECT_EQ(*s.tracks[0], 0.0);           // used: the next repeats start anew
  EXPECT_TRUE(s.Scan(0, test, streak));
  EXPECT_NEAR(*s.tracks[0], std::log(0.05), 1e-9);
  EXPECT_FALSE(s.Scan(1, test, streak));  // landmark 0's held pairing is distinct evidence: 0.0025
  HeldStreak alone;
  EXPECT_TRUE(s.Scan(1, test, alone));    // no track: 0.05, and its repeat is no evidence
  EXPECT_TRUE(s.Scan(1, test, alone));
  EXPECT_FALSE(s.tracks[1].has_value());
  // kDistinctLandmarks: tracks are no evidence and are left as they are.
  s.tracks = {0.0, std::nullopt};
  const HoldTest landmarks{kGate, s.DensityFor(0.05, 0), HoldEvidence::kDistinctLandmarks};
  HeldStreak other;
  EXPECT_TRUE(s.Scan(0, landmarks, other));
  EXPECT_TRUE(s.Scan(0, landmarks, other));
  EXPECT_EQ(*s.tracks[0], 0.0);
}

}  // namespace
}  // namespace slambox
