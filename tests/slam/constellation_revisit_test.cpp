// The revisit search over windows of travel (slam/constellation_revisit.hpp): which
// landmarks are old and recent, the heading prior, the search trigger and the missed-landmark
// refusal's closed form, the shares of the motion and their screw.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <random>
#include <vector>

#include "slam/constellation_revisit.hpp"

namespace slambox {
namespace {

/// 12 old landmarks seen until travel 10 m, the same 12 mapped again (moved by `drift`)
/// created at travel 100 m; the robot is at travel 110 m with range_max 10 m (windows 20,
/// 40, 80 m: the first already separates old from recent).
std::vector<RevisitLandmark> TwoMaps(const SE2& drift) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-15.0, 15.0);
  std::vector<RevisitLandmark> out;
  for (int k = 0; k < 12; ++k) out.push_back({Eigen::Vector2d(u(rng), u(rng)), 0.0, 10.0, 0.01});
  for (int k = 0; k < 12; ++k) out.push_back({drift.inverse() * out[k].xy, 100.0, 110.0, 0.2});
  return out;
}

RevisitSettings Settings() {
  return {.travel_m = 110.0, .heading_variance_rad2 = 0.2, .range_max_m = 10.0, .tolerance_m = 0.5,
          .gate_probability = 0.99, .max_hypotheses = 0};
}

TEST(ConstellationRevisit, TheRecentMapIsMatchedOntoTheOldInTheNarrowestWindow) {
  const SE2 drift(3.0, -2.0, 0.1);
  const std::vector<RevisitLandmark> maps = TwoMaps(drift);
  const std::optional<Revisit> r = FindRevisit(maps, Settings());
  ASSERT_TRUE(r.has_value());
  EXPECT_DOUBLE_EQ(r->window_m, 20.0);
  ASSERT_EQ(r->old.size(), 12u);
  ASSERT_EQ(r->recent.size(), 12u);
  EXPECT_EQ(r->match.pairs.size(), 12u);
  for (const auto& [o, c] : r->match.pairs) EXPECT_EQ(r->recent[c], r->old[o] + 12);
  EXPECT_NEAR(r->match.T_old_recent.x, drift.x, 1e-9);
  EXPECT_NEAR(r->match.T_old_recent.y, drift.y, 1e-9);
  EXPECT_NEAR(r->match.T_old_recent.theta, drift.theta, 1e-9);
}

TEST(ConstellationRevisit, ATurnBeyondTheHeadingDriftSinceTheOldWereSeenIsNoHypothesis) {
  // Heading variance since the old landmarks were seen: 0.2 - 0.01 rad^2, a 99 % gate of
  // sqrt(6.63 * 0.19) = 1.12 rad. A turn of 1.3 rad is outside, 1.0 inside.
  EXPECT_FALSE(FindRevisit(TwoMaps(SE2(3.0, -2.0, 1.3)), Settings()).has_value());
  EXPECT_TRUE(FindRevisit(TwoMaps(SE2(3.0, -2.0, 1.0)), Settings()).has_value());
}

TEST(ConstellationRevisit, AShiftOfTheRobotBeyondTheHeadingDriftOverTheTravelIsNoHypothesis) {
  // Heading variance since the old landmarks were seen 1e-4 rad^2 over 100 m of travel: the
  // robot (at the origin) may move by sqrt(chi2_2(0.99) * 1e-4) * 100 = 3.03 m. A drift of
  // (3, -2) moves it 3.6 m, one of (2, -1) 2.24 m.
  RevisitSettings settings = Settings();
  settings.heading_variance_rad2 = 0.0101;
  EXPECT_FALSE(FindRevisit(TwoMaps(SE2(3.0, -2.0, 0.01)), settings).has_value());
  EXPECT_TRUE(FindRevisit(TwoMaps(SE2(2.0, -1.0, 0.01)), settings).has_value());
  // Measured at the robot: a turn by 0.02 rad about the origin leaves a robot there in place
  // and moves one at (200, 0) by 4 m.
  EXPECT_TRUE(FindRevisit(TwoMaps(SE2(0.0, 0.0, 0.02)), settings).has_value());
  settings.robot_xy = Eigen::Vector2d(200.0, 0.0);
  EXPECT_FALSE(FindRevisit(TwoMaps(SE2(0.0, 0.0, 0.02)), settings).has_value());
}

TEST(ConstellationRevisit, FewerThanThreeOldLandmarksEndTheSearch) {
  std::vector<RevisitLandmark> maps = TwoMaps(SE2(1.0, 0.0, 0.0));
  maps.erase(maps.begin() + 2, maps.begin() + 12);  // 2 old, 12 recent
  EXPECT_FALSE(FindRevisit(maps, Settings()).has_value());
}

TEST(ConstellationRevisit, ASearchIsWorthItOnlyWhenALandmarkJoinedTheWidestWindow) {
  const std::vector<RevisitLandmark> maps = TwoMaps(SE2(1.0, 0.0, 0.0));
  std::vector<int> keys(maps.size());
  for (size_t k = 0; k < keys.size(); ++k) keys[k] = static_cast<int>(k);
  std::vector<int> searched;
  EXPECT_TRUE(RevisitWorthSearching(maps, keys, Settings(), searched));
  EXPECT_EQ(searched.size(), 12u);  // created within 80 m of travel: the recent 12
  EXPECT_FALSE(RevisitWorthSearching(maps, keys, Settings(), searched));
  std::vector<RevisitLandmark> more = maps;
  more.push_back({Eigen::Vector2d(0, 0), 109.0, 110.0, 0.2});
  keys.push_back(99);
  EXPECT_TRUE(RevisitWorthSearching(more, keys, Settings(), searched));
  EXPECT_EQ(searched.size(), 13u);
}

TEST(ConstellationRevisit, AnOldLandmarkInViewAndNeverMappedCostsOneMinusPdPerScan) {
  // Old landmarks 0..2 are paired; old landmark 3 at (5, 0) is not. Under the identity match
  // it lies 5 m ahead of each of 4 scan poses at the origin; P_D 0.9 in view gives
  // log(0.1) per scan. A window landmark within tolerance of it, or a detector that does not
  // see it, costs nothing.
  std::vector<RevisitLandmark> confirmed = {{{0, 1}}, {{1, 0}}, {{0, -1}}, {{5, 0}}};
  Revisit r;
  r.old = {0, 1, 2, 3};
  r.match.pairs = {{0, 0}, {1, 1}, {2, 2}};
  const std::vector<SE2> scans(4, SE2());
  auto pd = [](const Eigen::Vector2d& z) { return z.x() < 10.0 ? 0.9 : 0.0; };
  const std::vector<Eigen::Vector2d> window = {{0, 1}, {1, 0}, {0, -1}};
  EXPECT_NEAR(LogMissedUnderRevisit(r, confirmed, window, scans, 0.5, {}, pd), 4.0 * std::log(0.1), 1e-12);
  std::vector<Eigen::Vector2d> with_it = window;
  with_it.emplace_back(5.3, 0.0);
  EXPECT_EQ(LogMissedUnderRevisit(r, confirmed, with_it, scans, 0.5, {}, pd), 0.0);
  auto blind = [](const Eigen::Vector2d&) { return 0.0; };
  EXPECT_EQ(LogMissedUnderRevisit(r, confirmed, window, scans, 0.5, {}, blind), 0.0);

  // Under a match T that shifts by (20, 0), old landmark 3 is expected at T^-1 (5, 0) =
  // (-15, 0): out of view. Mapped during the drift with share 1 it moves with the window and
  // is expected at (5, 0) again; with share 1/2 at (-5, 0), 5 m behind, out of the 180 degree
  // view.
  r.match.T_old_recent = SE2(20.0, 0.0, 0.0);
  auto pd_ahead = [](const Eigen::Vector2d& z) { return z.x() < 10.0 && std::abs(z.y()) <= M_PI / 2 ? 0.9 : 0.0; };
  EXPECT_EQ(LogMissedUnderRevisit(r, confirmed, window, scans, 0.5, {}, pd_ahead), 0.0);
  const std::vector<double> all = {0, 0, 0, 1}, half = {0, 0, 0, 0.5};
  EXPECT_NEAR(LogMissedUnderRevisit(r, confirmed, window, scans, 0.5, all, pd_ahead), 4.0 * std::log(0.1), 1e-12);
  EXPECT_EQ(LogMissedUnderRevisit(r, confirmed, window, scans, 0.5, half, pd_ahead), 0.0);
  EXPECT_NEAR(RevisitTolerance(Eigen::Vector2d(0.01, 1e-4).asDiagonal(), 20.0, 9.21),
              std::sqrt(2.0 * 9.21 * 0.04), 1e-12);
}

TEST(ConstellationRevisit, LandmarksMappedDuringTheDriftTakeTheirShareOfTheMotion) {
  // Heading variance 0.01 rad^2 when the paired old landmarks were last seen (the largest of
  // them), 0.05 now: a landmark seen at 0.02 takes (0.02 - 0.01) / (0.05 - 0.01) = 1/4;
  // seen before the paired ones, none; the paired ones, none.
  EXPECT_DOUBLE_EQ(RevisitShare(0.02, 0.01, 0.05), 0.25);
  EXPECT_EQ(RevisitShare(0.005, 0.01, 0.05), 0.0);
  EXPECT_EQ(RevisitShare(0.06, 0.01, 0.05), 1.0);
  EXPECT_EQ(RevisitShare(0.02, 0.05, 0.05), 0.0);  // no drift since: nothing to share
  std::vector<RevisitLandmark> confirmed = {{{0, 1}, 0, 1, 0.008}, {{1, 0}, 0, 2, 0.01}, {{0, -1}, 0, 2, 0.01},
                                            {{5, 0}, 0, 40, 0.02},  {{9, 9}, 0, 0, 0.0}};
  Revisit r;
  r.old = {0, 1, 2, 3, 4};
  r.match.pairs = {{0, 0}, {1, 1}, {2, 2}};
  RevisitSettings settings = Settings();
  settings.heading_variance_rad2 = 0.05;
  const std::vector<double> shares = RevisitShares(r, confirmed, settings);
  ASSERT_EQ(shares.size(), 5u);
  EXPECT_EQ(shares[0], 0.0);
  EXPECT_EQ(shares[1], 0.0);
  EXPECT_EQ(shares[2], 0.0);
  EXPECT_DOUBLE_EQ(shares[3], 0.25);
  EXPECT_EQ(shares[4], 0.0);
}

TEST(ConstellationRevisit, PartOfAMotionFollowsItsScrew) {
  const SE2 T(3.0, -2.0, 0.4);
  const SE2 none = PartOfMotion(T, 0.0);
  EXPECT_EQ(none.x, 0.0);
  EXPECT_EQ(none.theta, 0.0);
  const SE2 all = PartOfMotion(T, 1.0);  // exactly T
  EXPECT_EQ(all.x, T.x);
  EXPECT_EQ(all.y, T.y);
  EXPECT_EQ(all.theta, T.theta);
  // Two halves make the whole; a quarter turns by a quarter of the angle about the same fixed
  // point (the motion's centre of rotation c = (I - R)^-1 t stays put).
  const SE2 half = PartOfMotion(T, 0.5);
  const SE2 twice = half * half;
  EXPECT_NEAR(twice.x, T.x, 1e-12);
  EXPECT_NEAR(twice.y, T.y, 1e-12);
  EXPECT_NEAR(twice.theta, T.theta, 1e-12);
  const Eigen::Vector2d c = (Eigen::Matrix2d::Identity() - T.rotation()).inverse() * T.translation();
  const SE2 quarter = PartOfMotion(T, 0.25);
  EXPECT_NEAR(quarter.theta, 0.1, 1e-12);
  EXPECT_NEAR((quarter * c - c).norm(), 0.0, 1e-12);
  // A pure translation is shared linearly.
  const SE2 shift = PartOfMotion(SE2(4.0, -2.0, 0.0), 0.25);
  EXPECT_NEAR(shift.x, 1.0, 1e-12);
  EXPECT_NEAR(shift.y, -0.5, 1e-12);
}

}  // namespace
}  // namespace slambox
