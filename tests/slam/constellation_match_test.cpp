// Constellation matching (slam/constellation_match.hpp): the binomial tail against closed
// forms, a drifted revisit of a random park found with its motion and pairs, no match
// between unrelated random constellations, none on a regular lattice (every shift fits).
#include "slam/constellation_match.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace slambox {
namespace {

TEST(ConstellationMatch, BinomialUpperTailClosedForms) {
  EXPECT_DOUBLE_EQ(BinomialUpperTail(3, 0.5, 0), 1.0);
  EXPECT_NEAR(BinomialUpperTail(3, 0.5, 2), 0.5, 1e-12);     // (3 + 1) / 8
  EXPECT_NEAR(BinomialUpperTail(4, 0.1, 4), 1e-4, 1e-16);    // p^4
  EXPECT_NEAR(BinomialUpperTail(5, 0.2, 1), 1 - std::pow(0.8, 5), 1e-12);
  EXPECT_DOUBLE_EQ(BinomialUpperTail(3, 0.5, 4), 0.0);
}

std::vector<Eigen::Vector2d> RandomPark(int n, double width_m, double height_m, std::mt19937& rng) {
  std::uniform_real_distribution<double> x(0, width_m), y(0, height_m);
  std::vector<Eigen::Vector2d> p(n);
  for (auto& q : p) q = {x(rng), y(rng)};
  return p;
}

TEST(ConstellationMatch, FindsADriftedRevisitOfARandomPark) {
  std::mt19937 rng(7);
  const std::vector<Eigen::Vector2d> old = RandomPark(45, 80, 60, rng);  // the forest's density
  // The revisit maps 8 trees near (20, 20) again, 3 m and 25 degrees off, with 0.1 m of
  // noise, and two clutter points; recent = drift^-1 * old.
  const SE2 drift(3.0, -2.0, 25.0 * M_PI / 180);
  std::normal_distribution<double> noise(0.0, 0.1);
  std::vector<Eigen::Vector2d> recent;
  std::vector<int> truth;
  for (size_t i = 0; i < old.size() && recent.size() < 8; ++i)
    if ((old[i] - Eigen::Vector2d(20, 20)).norm() < 15) {
      recent.push_back(drift.inverse() * old[i] + Eigen::Vector2d(noise(rng), noise(rng)));
      truth.push_back(static_cast<int>(i));
    }
  ASSERT_EQ(recent.size(), 8u);
  recent.push_back({-30, 5});
  recent.push_back({-10, -25});
  const auto match = MatchConstellation(old, recent, {.tolerance_m = 0.9});
  ASSERT_TRUE(match.has_value());
  EXPECT_NEAR(match->T_old_recent.x, drift.x, 0.2);
  EXPECT_NEAR(match->T_old_recent.y, drift.y, 0.2);
  EXPECT_NEAR(match->T_old_recent.theta, drift.theta, 0.02);
  ASSERT_EQ(match->pairs.size(), 8u);
  for (const auto& [o, r] : match->pairs) EXPECT_EQ(o, truth[r]);
  EXPECT_LT(match->chance, 0.01);
  EXPECT_GT(match->hypotheses, 0);
}

TEST(ConstellationMatch, UnrelatedRandomConstellationsNeverMatch) {
  std::mt19937 rng(11);
  int accepted = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const std::vector<Eigen::Vector2d> old = RandomPark(45, 80, 60, rng);
    const std::vector<Eigen::Vector2d> recent = RandomPark(10, 20, 20, rng);
    accepted += MatchConstellation(old, recent, {.tolerance_m = 0.9}).has_value() ? 1 : 0;
  }
  EXPECT_EQ(accepted, 0);
}

TEST(ConstellationMatch, ALatticeIsAmbiguous) {
  std::vector<Eigen::Vector2d> old;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) old.emplace_back(5.0 * i, 5.0 * j);
  // Six lattice points seen 1 m off: every shift by a lattice vector fits as well.
  std::vector<Eigen::Vector2d> recent;
  for (int i = 3; i < 6; ++i)
    for (int j = 3; j < 5; ++j) recent.emplace_back(5.0 * i + 1.0, 5.0 * j);
  EXPECT_FALSE(MatchConstellation(old, recent, {.tolerance_m = 0.9}).has_value());
  // The block is symmetric itself (half a turn maps it onto itself, pairing it differently):
  // ambiguous even once in a random park. Without the symmetry (one corner moved) it is found.
  std::mt19937 rng(3);
  std::vector<Eigen::Vector2d> park = RandomPark(40, 80, 60, rng);
  for (const Eigen::Vector2d& r : recent) park.push_back(r + Eigen::Vector2d(99.0, 0.0));
  EXPECT_FALSE(MatchConstellation(park, recent, {.tolerance_m = 0.9}).has_value());
  recent.back() += Eigen::Vector2d(2.0, 1.5);
  park.back() += Eigen::Vector2d(2.0, 1.5);
  const auto match = MatchConstellation(park, recent, {.tolerance_m = 0.9});
  ASSERT_TRUE(match.has_value());
  EXPECT_EQ(match->pairs.size(), 6u);
  EXPECT_NEAR(match->T_old_recent.x, 99.0, 1e-9);
  EXPECT_NEAR(match->T_old_recent.theta, 0.0, 1e-9);
}

TEST(ConstellationMatch, TwoRecentLandmarksAreNoConstellation) {
  const std::vector<Eigen::Vector2d> old = {{0, 0}, {5, 0}, {0, 7}, {9, 9}};
  const std::vector<Eigen::Vector2d> recent = {{0, 0}, {5, 0}};
  EXPECT_FALSE(MatchConstellation(old, recent, {.tolerance_m = 0.9}).has_value());
}

}  // namespace
}  // namespace slambox
