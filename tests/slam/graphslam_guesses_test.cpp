// GraphSLAM's end solve from the best of its guesses (slam/graphslam_guesses.cpp): the margin
// a guess must beat, the lowest chi2 kept among the filtered, re-localized, periodically
// solved and replayed guesses, periodic solves past the keyframe cap, and replays only where
// the fit is worse than the noise model or the guesses disagree (small synthetic landmark
// streams, fixed seeds).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "slam/graphslam.hpp"
#include "tests/support/landmark_world.hpp"

namespace slambox {
namespace {

using testing::AteRmse;
using testing::LandmarkOptions;
using testing::LandmarkWorld;
using testing::MakeSyntheticStream;

Estimate RunGraphSlam(const Stream& stream, const GraphSlamConfig& config) {
  GraphSlam m(config);
  return Replay(m, stream);
}

// The end solve starts from each of its guesses in turn (filtered, relocalized, with periodic
// solves incremental, where the best fits badly three replays); a later one is kept only where
// it fits better (FitsBetter).
const std::vector<const char*> kLaterGuesses = {"relocalized", "incremental", "replayed_half", "replayed",
                                                "replayed_double"};
// Returns the name of the guess that must have been kept.
std::string ExpectedEndGuess(const Estimate& g) {
  std::string kept = "filtered";
  double chi2 = g.diagnostics.at("end_guess_chi2_filtered").back().second;
  for (const char* name : kLaterGuesses) {
    const auto it = g.diagnostics.find(std::string("end_guess_chi2_") + name);
    if (it == g.diagnostics.end()) continue;
    if (FitsBetter(it->second.back().second, chi2)) kept = name, chi2 = it->second.back().second;
  }
  return kept;
}

// `same_graph`: known ids (with unknown ids the smoother's merges change the graph after it).
void ExpectTheEndSolveKeptTheLowestChi2(const Estimate& g, bool same_graph = true) {
  const std::string kept = ExpectedEndGuess(g);
  double lowest = INFINITY;
  std::vector<const char*> names = {"filtered"};
  names.insert(names.end(), kLaterGuesses.begin(), kLaterGuesses.end());
  for (const char* name : names) {
    const auto it = g.diagnostics.find(std::string("end_guess_chi2_") + name);
    if (it == g.diagnostics.end()) continue;
    std::printf("end solve from the %s guess: chi2 %.8g\n", name, it->second.back().second);
    lowest = std::min(lowest, it->second.back().second);
    if (std::string(name) != "filtered") {
      EXPECT_EQ(g.diagnostics.at(std::string("end_guess_") + name).back().second, kept == name ? 1.0 : 0.0) << name;
    }
  }
  if (same_graph) {
    EXPECT_FALSE(FitsBetter(lowest, g.diagnostics.at("chi2_final").back().second));  // no guess fits better
  }
}

TEST(GraphSlam, FitsBetterOnlyBeyondTheSolversToleranceAndOneChi2Unit) {
  EXPECT_TRUE(FitsBetter(3989.0, 2.698e6));
  EXPECT_FALSE(FitsBetter(46203.17, 46203.27));  // landmarks seed 1: one minimum, two stops
  EXPECT_FALSE(FitsBetter(100.0, 100.5));        // below one unit
  EXPECT_TRUE(FitsBetter(100.0, 101.5));
  EXPECT_FALSE(FitsBetter(2.0e7, 2.0e7 + 15.0));  // below the relative tolerance (20)
  EXPECT_TRUE(FitsBetter(2.0e7, 2.0e7 + 25.0));
  EXPECT_FALSE(FitsBetter(5.0, 5.0));
}

TEST(GraphSlam, PeriodicSolvesEndFromTheGuessOfTheLowestChi2) {
  // Known ids: the end solve starts from the guess of the lowest chi2 (the front end's
  // filtered poses, those re-localized against its map, the periodically solved graph;
  // each solved under the same association) and goes on from there.
  const Stream stream = MakeSyntheticStream(LandmarkOptions(7, 2, true), LandmarkWorld());
  GraphSlamConfig config;
  config.solve_every_keyframes = 100;
  const Estimate g = RunGraphSlam(stream, config);
  ASSERT_TRUE(g.diagnostics.count("end_guess_chi2_incremental"));
  ASSERT_TRUE(g.diagnostics.count("end_guess_chi2_relocalized"));
  ExpectTheEndSolveKeptTheLowestChi2(g);
}

TEST(GraphSlam, PeriodicSolvesPastTheCapSolveADecimatedGraphLessOften) {
  // periodic_max_keyframes: past the cap a solve during the run keeps every k-th keyframe
  // (k = ceil(keyframes / cap)) and comes every solve_every_keyframes x k keyframes; the end
  // solve is the full graph's, so the result stays as good as with every keyframe solved.
  const Stream stream = MakeSyntheticStream(LandmarkOptions(7, 2, true), LandmarkWorld());
  GraphSlamConfig full;
  full.solve_every_keyframes = 50;
  full.periodic_max_keyframes = 0;
  GraphSlamConfig capped = full;
  capped.periodic_max_keyframes = 150;
  const Estimate a = RunGraphSlam(stream, full), b = RunGraphSlam(stream, capped);
  const auto keyframes = static_cast<int>(b.diagnostics.at("num_keyframes").back().second);
  int expected_solves = 0;  // the schedule, keyframe by keyframe (every scan is one here)
  for (int k = 1, last = 0; k < keyframes; ++k)
    if (k - last >= 50 * ((k + 150) / 150)) ++expected_solves, last = k;
  ASSERT_GT(keyframes, 600);  // the cap is reached: strides 2 and more occur
  EXPECT_EQ(a.diagnostics.at("solver_iterations").size(), static_cast<size_t>((keyframes - 1) / 50 + 1));
  EXPECT_EQ(b.diagnostics.at("solver_iterations").size(), static_cast<size_t>(expected_solves + 1));
  std::printf("keyframes %d; periodic solves %zu (all keyframes) / %d (capped); ATE %.4f / %.4f m\n", keyframes,
              a.diagnostics.at("solver_iterations").size() - 1, expected_solves, AteRmse(stream, a), AteRmse(stream, b));
  EXPECT_LT(AteRmse(stream, b), 1.05 * AteRmse(stream, a));
  ExpectTheEndSolveKeptTheLowestChi2(b);
}

TEST(GraphSlam, TheGrowthIsReplayedOnlyWhereTheBestGuessFitsWorseThanTheNoiseModel) {
  // replay_chi2_per_residual: this run fits its noise model (chi2 per residual below 1) and
  // its two guesses end in one minimum, so by default nothing is replayed; with the threshold
  // below its chi2 per residual the three replays are solved too and the lowest chi2 of all
  // five guesses is kept.
  const Stream stream = MakeSyntheticStream(LandmarkOptions(7, 2, true), LandmarkWorld());
  const Estimate plain = RunGraphSlam(stream, GraphSlamConfig{});
  const double per_residual = plain.diagnostics.at("chi2_per_residual").back().second;
  EXPECT_LT(per_residual, GraphSlamConfig{}.replay_chi2_per_residual);
  const double filtered = plain.diagnostics.at("end_guess_chi2_filtered").back().second;
  const double relocalized = plain.diagnostics.at("end_guess_chi2_relocalized").back().second;
  EXPECT_FALSE(FitsBetter(std::min(filtered, relocalized), std::max(filtered, relocalized)));
  EXPECT_EQ(plain.diagnostics.at("end_guesses_disagree").back().second, 0.0);
  for (const char* name : {"replayed_half", "replayed", "replayed_double"})
    EXPECT_FALSE(plain.diagnostics.count(std::string("end_guess_chi2_") + name)) << name;
  GraphSlamConfig replaying;
  replaying.replay_chi2_per_residual = 0.5 * per_residual;
  const Estimate g = RunGraphSlam(stream, replaying);
  for (const char* name : {"replayed_half", "replayed", "replayed_double"})
    ASSERT_TRUE(g.diagnostics.count(std::string("end_guess_chi2_") + name)) << name;
  ExpectTheEndSolveKeptTheLowestChi2(g);
  // Each replay ends in this run's one minimum (the data fit): chi2 within 0.1 % of the default's.
  const double chi2 = plain.diagnostics.at("chi2_final").back().second;
  for (const char* name : {"replayed_half", "replayed", "replayed_double"})
    EXPECT_NEAR(g.diagnostics.at(std::string("end_guess_chi2_") + name).back().second, chi2, 1e-3 * chi2) << name;
  EXPECT_LT(AteRmse(stream, g), 1.05 * AteRmse(stream, plain));
}

TEST(GraphSlam, RelocalizedGuessKeptOnlyWhereItsChi2IsLower) {
  // Default settings (no periodic solves), known and unknown ids: two guesses, the lower kept.
  for (const bool known_ids : {true, false}) {
    const Stream stream = MakeSyntheticStream(LandmarkOptions(3, 2, known_ids), LandmarkWorld());
    const Estimate g = RunGraphSlam(stream, GraphSlamConfig{});
    ASSERT_TRUE(g.diagnostics.count("end_guess_chi2_relocalized"));
    EXPECT_FALSE(g.diagnostics.count("end_guess_chi2_incremental"));
    ExpectTheEndSolveKeptTheLowestChi2(g, known_ids);
    GraphSlamConfig off;
    off.relocalized_guess = false;
    EXPECT_FALSE(RunGraphSlam(stream, off).diagnostics.count("end_guess_chi2_relocalized"));
  }
}

}  // namespace
}  // namespace slambox
