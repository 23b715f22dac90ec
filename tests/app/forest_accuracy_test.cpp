// Landmark SLAM on the built-in `forest` (issue 14: 45 trees, 180 deg detector, 12 m,
// unknown ids, clutter 0.2 / scan, detection 0.95, 400 m) at fixed seeds 3 and 6:
// graphslam >= 5x and ekf-slam >= 2x better than dead reckoning, maps without spurious
// landmarks or duplicates. Measured (slambox sweep scenarios/forest_sweep.yaml): odometry
// 5.07 / 8.25 m, ekf-slam 0.81 / 1.12, graphslam 0.42 / 0.31, no spurious landmark. Before
// tentative landmarks expired, graphslam gave 2.55 / 2.00 m with 17 / 55 spurious (the test
// fails there). Seed 1 failed the loop closure before closure_test (test below).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <tuple>
#include <vector>
#include <variant>

#include "app/registry.hpp"
#include "eval/consistency.hpp"
#include "sim/simulate.hpp"

namespace slambox {
namespace {

double AteRmse(const Estimate& e, const Stream& s) {
  std::map<double, SE2> gt;
  for (const auto& g : s.groundtruth) gt[g.t_s] = g.pose;
  double sum = 0.0;
  int n = 0;
  for (const auto& p : e.trajectory)
    if (auto it = gt.find(p.t_s); it != gt.end()) sum += (p.pose.translation() - it->second.translation()).squaredNorm(), ++n;
  return std::sqrt(sum / n);
}

struct MapScore {
  int spurious = 0;    ///< estimated landmarks farther than 1 m from every tree
  int duplicates = 0;  ///< extra estimates within 1 m of a tree that already has one
};
MapScore ScoreMap(const Estimate& e, const Scenario& scenario) {
  MapScore score;
  std::map<int, int> per_tree;
  for (const auto& l : e.landmarks) {
    int nearest = -1;
    double best = 1.0;
    for (size_t t = 0; t < scenario.landmarks.size(); ++t)
      if (const double d = (scenario.landmarks[t].pos - l.position).norm(); d < best) best = d, nearest = static_cast<int>(t);
    if (nearest < 0) ++score.spurious;
    else if (++per_tree[nearest] > 1) ++score.duplicates;
  }
  return score;
}

struct Result {
  double odometry = 0.0, ekf = 0.0, graph = 0.0;
  MapScore ekf_map, graph_map;
};

Result RunForest(std::uint64_t seed) {
  const Scenario scenario = LoadScenario("forest");
  const Stream s = Simulate(scenario, seed);
  const auto run = [&](const std::string& name) {
    auto module = FindModule(name).create({});
    return Replay(*module, s);
  };
  Result r;
  r.odometry = AteRmse(run("odometry"), s);
  const Estimate ekf = run("ekf-slam"), graph = run("graphslam");
  r.ekf = AteRmse(ekf, s);
  r.graph = AteRmse(graph, s);
  r.ekf_map = ScoreMap(ekf, scenario);
  r.graph_map = ScoreMap(graph, scenario);
  std::printf("seed %lu: odometry %.2f ekf-slam %.2f (%d spurious, %d duplicates) graphslam %.2f (%d, %d)\n",
              static_cast<unsigned long>(seed), r.odometry, r.ekf, r.ekf_map.spurious, r.ekf_map.duplicates, r.graph,
              r.graph_map.spurious, r.graph_map.duplicates);
  return r;
}

struct GraphRun {
  double ate = 0.0;
  MapScore map;
};

/// graphslam alone on `forest` at `seed`, with module parameters `params` and scenario
/// overrides `scenario_overrides` ("dotted.key=value").
GraphRun RunGraphSlam(std::uint64_t seed, const ParamOverrides& params = {},
                      const std::vector<std::string>& scenario_overrides = {}) {
  const Scenario scenario = LoadScenario("forest", scenario_overrides);
  const Stream s = Simulate(scenario, seed);
  const Estimate graph = Replay(*FindModule("graphslam").create(params), s);
  const GraphRun r{AteRmse(graph, s), ScoreMap(graph, scenario)};
  std::printf("seed %lu: graphslam %.2f (%d spurious, %d duplicates)\n", static_cast<unsigned long>(seed), r.ate,
              r.map.spurious, r.map.duplicates);
  return r;
}

TEST(ForestAccuracy, UnknownIdsWithClutter) {
  for (std::uint64_t seed : {3u, 6u}) {
    const Result r = RunForest(seed);
    SCOPED_TRACE(seed);
    EXPECT_LT(r.graph, r.odometry / 5.0);
    EXPECT_LT(r.ekf, r.odometry / 2.0);
    EXPECT_EQ(r.graph_map.spurious, 0);
    EXPECT_EQ(r.graph_map.duplicates, 0);
    EXPECT_LE(r.ekf_map.spurious + r.ekf_map.duplicates, 1);
  }
}

TEST(ForestAccuracy, HeldUncertainPairingsCloseTheLoop) {
  // Seeds 10 and 16 (held out when the rule was designed on seed 0) failed the loop
  // closure without hold_uncertain_pairings (graphslam 7.33 and 7.08 m, 49 and 46 spurious
  // landmarks). Measured with hold_evidence=landmarks (the default): graphslam 0.38 / 0.42 m,
  // ekf-slam 1.23 / 1.00 m, one duplicate tree on seed 10 (with hold_evidence=scans, the
  // rule before: 0.22 / 0.45 and 1.09 / 0.92 m, none). Bounds: 1.5x the measured ATE.
  const std::map<std::uint64_t, std::pair<double, double>> bound = {{10u, {0.57, 1.85}}, {16u, {0.63, 1.50}}};
  for (const auto& [seed, b] : bound) {
    const Result r = RunForest(seed);
    SCOPED_TRACE(seed);
    EXPECT_LT(r.graph, b.first);
    EXPECT_LT(r.ekf, b.second);
    EXPECT_LE(r.graph_map.spurious + r.graph_map.duplicates, seed == 10u ? 1 : 0);
  }
}

TEST(ForestAccuracy, DistinctLandmarksCloseTheLoop) {
  // Seeds 0 and 47 failed the loop closure with hold_evidence=scans (graphslam 5.52 and
  // 7.26 m, 70 and 73 spurious landmarks: a tree never mapped in lap 1 sat in an old
  // tree's gate for several scans and its repeats let the lone pairing through). Measured
  // with hold_evidence=landmarks: graphslam 0.17 / 0.50 m (known ids 0.20 / 0.55), no
  // spurious landmark, ekf-slam 1.26 / 0.96 m. Bounds: 1.5x the measured ATE.
  const std::map<std::uint64_t, std::pair<double, double>> bound = {{0u, {0.26, 1.89}}, {47u, {0.75, 1.44}}};
  for (const auto& [seed, b] : bound) {
    const Result r = RunForest(seed);
    SCOPED_TRACE(seed);
    EXPECT_LT(r.graph, b.first);
    EXPECT_LT(r.ekf, b.second);
    EXPECT_EQ(r.graph_map.spurious + r.graph_map.duplicates, 0);
  }
}

TEST(ForestAccuracy, ClosureTestRejectsTheFalseLoopClosureOfSeed1) {
  // Seed 1: at 193.6 s JCBB paired a tree never mapped in lap 1 (tree 8) with the first
  // landmark (tree 12) and a clutter detection with tree 1's, each pinning the other down;
  // ekf-slam jumped 6 m and mapped the park again (6.70 m, 72 spurious landmarks, odometry
  // 10.97 m). With closure_test (slam/README_landmark_slam.md) that closure forks the
  // filter, the branch without it explains the next scan better and goes on; the loop closes
  // at 195 s through a merge whose test is kept: measured 0.97 m, no spurious landmark.
  // Bound: 1.5x the measured ATE.
  const Scenario scenario = LoadScenario("forest");
  const Stream s = Simulate(scenario, 1);
  const Estimate odometry = Replay(*FindModule("odometry").create({}), s);
  const Estimate ekf = Replay(*FindModule("ekf-slam").create({}), s);
  const double ate = AteRmse(ekf, s);
  std::printf("seed 1: odometry %.2f ekf-slam %.2f\n", AteRmse(odometry, s), ate);
  EXPECT_LT(ate, 1.46);
  EXPECT_LT(ate, AteRmse(odometry, s) / 2.0);
  const MapScore map = ScoreMap(ekf, scenario);
  EXPECT_LE(map.spurious + map.duplicates, 1);
  // A closure was rejected and one kept; the estimate of the surviving branch is whole.
  ASSERT_TRUE(ekf.diagnostics.count("closure_kept"));
  const auto& kept = ekf.diagnostics.at("closure_kept");
  EXPECT_TRUE(std::any_of(kept.begin(), kept.end(), [](const auto& p) { return p.second == 0.0; }));
  EXPECT_TRUE(std::any_of(kept.begin(), kept.end(), [](const auto& p) { return p.second == 1.0; }));
  for (size_t k = 1; k < ekf.trajectory.size(); ++k) ASSERT_LT(ekf.trajectory[k - 1].t_s, ekf.trajectory[k].t_s);
  size_t observations = 0;
  for (const auto& e : s.events)
    if (const auto* scan = std::get_if<LandmarkEvent>(&e)) observations += scan->observations.size();
  EXPECT_EQ(ekf.observation_assignments.size(), observations);
  // Without the test the old result comes back (the test fails there).
  const Estimate without = Replay(*FindModule("ekf-slam").create({{"closure_test", "false"}}), s);
  EXPECT_GT(AteRmse(without, s), 5.0);
}

TEST(ForestAccuracy, ClosureTestRunsWithoutConfiguredClutter) {
  // With clutter_per_scan 0 a gate can still hold a tree that was never mapped (Reid's
  // new-landmark density, measured by the filter), so the closure test still weighs an
  // uncertain loop closure. Seed 84 at clutter 0: measured 2.23 m (odometry 11.08 m); when
  // the test only counted configured clutter it never ran there and ekf-slam gave 6.02 m.
  // Bound: 1.5x the measured ATE.
  Scenario scenario = LoadScenario("forest");
  scenario.sensors.landmarks->clutter_per_scan = 0.0;
  const Stream s = Simulate(scenario, 84);
  const Estimate odometry = Replay(*FindModule("odometry").create({}), s);
  const Estimate ekf = Replay(*FindModule("ekf-slam").create({}), s);
  const double ate = AteRmse(ekf, s);
  std::printf("seed 84, no clutter: odometry %.2f ekf-slam %.2f\n", AteRmse(odometry, s), ate);
  EXPECT_LT(ate, 3.35);
  ASSERT_TRUE(ekf.diagnostics.count("closure_tests"));
  // Without the closure test (and without constellation_merges, which closes it later, at
  // 4.23 m) the loop is not closed.
  const Estimate without =
      Replay(*FindModule("ekf-slam").create({{"closure_test", "false"}, {"constellation_merges", "false"}}), s);
  EXPECT_GT(AteRmse(without, s), 5.0);
}

TEST(ForestAccuracy, ConstellationMatchesCloseTheEkfsLoop) {
  // ekf-slam mapped the park a second time on seeds 62 and 84 (11.10 and 5.72 m, odometry
  // 13.85 and 11.08 m, 72 and 56 spurious landmarks); the return is recognized by its shape
  // (constellation_merges, slam/ekf_slam_constellation.cpp): measured 4.00 and 2.79 m.
  // Bounds: 1.25x the measured ATE (the 2x-odometry target), and off: the old failure.
  for (const auto& [seed, measured_m] : {std::pair{62, 4.00}, std::pair{84, 2.79}}) {
    const Stream s = Simulate(LoadScenario("forest"), seed);
    const Estimate ekf = Replay(*FindModule("ekf-slam").create({}), s);
    EXPECT_LT(AteRmse(ekf, s), 1.25 * measured_m) << seed;
    ASSERT_TRUE(ekf.diagnostics.count("constellation_merges")) << seed;
    const Estimate off = Replay(*FindModule("ekf-slam").create({{"constellation_merges", "false"}}), s);
    EXPECT_GT(AteRmse(off, s), 5.0) << seed;
  }
}

TEST(ForestAccuracy, ConstellationSpreadMovesTheMapDrawnDuringTheDrift) {
  // A revisit's motion moved only the robot and the window's landmarks: the landmarks mapped
  // during the drift stayed where it had put them, and lap 2 followed them off again. With
  // their share of it (constellation_spread, RevisitShares in slam/constellation_revisit.hpp)
  // measured ekf-slam 3.20 -> 2.35 m (seed 13) and 5.34 -> 3.59 m (18); fastslam2 relaxes its
  // path instead (slam/fastslam_closure.hpp), 1.29 -> 0.64 m (9) and 1.53 -> 0.37 m (27)
  // (ekf-slam's default is off, fastslam's on). Bounds: 1.1x the measured ATE; off: 1.2x it or more.
  const std::vector<std::tuple<std::string, int, double>> cases = {
      {"ekf-slam", 13, 2.35}, {"ekf-slam", 18, 3.59}, {"fastslam2", 9, 0.64}, {"fastslam2", 27, 0.37}};
  for (const auto& [module, seed, measured_m] : cases) {
    const Stream s = Simulate(LoadScenario("forest"), seed);
    const double on = AteRmse(Replay(*FindModule(module).create({{"constellation_spread", "true"}}), s), s);
    const double off = AteRmse(Replay(*FindModule(module).create({{"constellation_spread", "false"}}), s), s);
    std::printf("%s seed %d: %.2f m, without the spread %.2f m\n", module.c_str(), seed, on, off);
    EXPECT_LT(on, 1.1 * measured_m) << module << " " << seed;
    EXPECT_GT(off, 1.2 * measured_m) << module << " " << seed;
  }
}

TEST(ForestAccuracy, FastSlamKeepsItsOldMapAndRecognizesTheRevisit) {
  // fastslam2 (50 particles) mapped the park a second time on seeds 17 and 20 (2.74 and
  // 6.01 m); with the revisit search on the best particle's map (constellation_merges) and
  // old confirmed landmarks kept through their misses (keep_confirmed), measured 0.78 and
  // 0.86 m; either alone: 2.74 and 4.23 m (constellation only) (slam/README_fastslam.md,
  // "Place recognition by constellation"); with the path relaxed at each revisit 0.39 and
  // 0.58 m, without keep_confirmed 2.74 and 1.51 m. Bounds: 1.25x the measured ATE; without
  // keep_confirmed, above 2x it.
  for (const auto& [seed, measured_m] : {std::pair{17, 0.39}, std::pair{20, 0.58}}) {
    const Stream s = Simulate(LoadScenario("forest"), seed);
    const Estimate fs = Replay(*FindModule("fastslam2").create({}), s);
    std::printf("seed %d: fastslam2 %.2f\n", seed, AteRmse(fs, s));
    EXPECT_LT(AteRmse(fs, s), 1.25 * measured_m) << seed;
    EXPECT_TRUE(fs.diagnostics.count("constellation_merges")) << seed;
    const Estimate no_keep = Replay(*FindModule("fastslam2").create({{"keep_confirmed", "false"}}), s);
    EXPECT_GT(AteRmse(no_keep, s), 2.0 * measured_m) << seed;
  }
}

TEST(ForestAccuracy, FastSlamClosesTheLoopOnReObservedLandmarks) {
  // Known ids: a collapsed particle set re-observes lap 1's start after drifting (seed 4: 8 m,
  // -11 deg at 160 s), moves its pose, and lap 2 then followed lap 1's bent map (4.67 m).
  // With the closure relaxing the particle's path and the map drawn along it
  // (closure_spread, slam/fastslam_closure.hpp): measured 0.81 m (seed 4) and 0.41 m (9, 1.14 m
  // without). Bounds: 1.25x the measured ATE; without, above 2x it.
  for (const auto& [seed, measured_m] : {std::pair{4, 0.81}, std::pair{9, 0.41}}) {
    Scenario scenario = LoadScenario("forest");
    scenario.sensors.landmarks->known_ids = true;
    const Stream s = Simulate(scenario, seed);
    const Estimate on = Replay(*FindModule("fastslam2").create({}), s);
    const Estimate off = Replay(*FindModule("fastslam2").create({{"closure_spread", "false"}}), s);
    std::printf("known ids, seed %d: fastslam2 %.2f m, without the closure %.2f m\n", seed, AteRmse(on, s), AteRmse(off, s));
    EXPECT_LT(AteRmse(on, s), 1.25 * measured_m) << seed;
    EXPECT_TRUE(on.diagnostics.count("closure_particles")) << seed;
    EXPECT_GT(AteRmse(off, s), 2.0 * measured_m) << seed;
  }
}

TEST(ForestAccuracy, SmootherMergesRepairFalseLoopClosures) {
  // Seeds 11, 14 and 18 failed with the front end's association alone (graphslam 3.88,
  // 3.06 and 5.55 m, 41, 30 and 46 spurious landmarks: lap 2 paired with the wrong lap-1
  // trees and then mapped again). The smoother splits the ambiguous re-observations and
  // merges them back jointly (slam/smoother_merges.hpp): measured 0.27 / 0.24 / 0.18 m,
  // 0 / 0 / 1 landmark_spurious (with the leftover joins 0.28 / 0.16 / 0.18 m). Bounds: 1.5x
  // the first measured ATE.
  const std::map<std::uint64_t, double> bound = {{11u, 0.41}, {14u, 0.37}, {18u, 0.27}};
  for (const auto& [seed, b] : bound) {
    const Result r = RunForest(seed);
    SCOPED_TRACE(seed);
    EXPECT_LT(r.graph, b);
    EXPECT_LE(r.graph_map.spurious + r.graph_map.duplicates, 1);
  }
}

TEST(ForestAccuracy, GraphSlamFrontEndTakesTheClosureTestsVerdict) {
  // graphslam's front end runs the closure test too; when a test ends in the rival branch,
  // the graph's observations of the scans since the fork are rebuilt from the winner's
  // assignments (both branches number new landmarks from one counter, so the loser's keys
  // may name other trees). Seed 45 (held out when the smoother merges were designed):
  // measured 0.24 m (0.28 with the leftover joins), 0 spurious; with the test off in the front end (as before) 5.61 m, 47
  // spurious: lap 2 mapped the park again. Bound: 1.5x the measured ATE.
  const GraphRun r = RunGraphSlam(45);
  EXPECT_LT(r.ate, 0.36);
  EXPECT_LE(r.map.spurious, 1);
  EXPECT_GT(RunGraphSlam(45, {{"closure_test", "false"}}).ate, 5.0);
}

TEST(ForestAccuracy, SplitSegmentsNeverTakeAKeyTheFrontEndMergedAway) {
  // Seed 3 without configured clutter: the front end merged its landmarks 57 and 58 into 24
  // and 25, so they left its tracks, and the re-observation split numbered its new segments
  // from the largest key still tracked + 1 = 57. Those segments' observations then resolved
  // to 24 and 25 (graphslam's GraphKey follows the front end's merges): wrong pairings the
  // split had just removed came back, the solve stopped at chi2 per residual 137 and the
  // run ended 5.97 m off with 55 spurious landmarks (`landmark_spurious`; odometry
  // 5.07 m). With new keys from the front end's key counter: measured 0.22 m, 0 spurious
  // (known ids 0.22 m; 0.23 m with the leftover joins).
  // Bound: 1.5x the measured ATE.
  const GraphRun r = RunGraphSlam(3, {}, {"sensors.landmarks.clutter_per_scan=0"});
  EXPECT_LT(r.ate, 0.34);
  EXPECT_LE(r.map.spurious + r.map.duplicates, 1);
}

TEST(ForestAccuracy, SmootherJoinsTheDetectionsTheFrontEndLeftOut) {
  // Seed 4 at clutter 0.5: the front end held ~200 detections at the loop closure (scans
  // 900-1100), so the unknown-id graph had 204 observations fewer than the known-id one and
  // ended rotated about the start: ATE 0.316 m against 0.143 m with known ids, aligned ATE
  // equal (0.068 m). With the leftovers joined (slam/leftover_association.hpp): measured
  // 0.184 m, 0 spurious. Bound: 1.5x the measured ATE; without the join it fails.
  const GraphRun r = RunGraphSlam(4, {}, {"sensors.landmarks.clutter_per_scan=0.5"});
  EXPECT_LT(r.ate, 0.28);
  EXPECT_LE(r.map.spurious + r.map.duplicates, 1);
  EXPECT_GT(RunGraphSlam(4, {{"smoother_leftovers", "false"}}, {"sensors.landmarks.clutter_per_scan=0.5"}).ate, 0.28);
}

TEST(ForestAccuracy, SmootherMergesDropPairsTheirHypothesisExplainsWorse) {
  // Seed 121 (held out when the smoother merges were designed): the hypothesis taken in the
  // second merge round grew 29 pairs whose last (the lap-1 tree at (8.3, 13.4) with the
  // lap-2 segment of the tree 7 m away, d^2 5.5, a gate holding 0.7 other trees) was wrong;
  // picked by size it gave 2.24 m and 36 spurious landmarks. Dropping each pair whose
  // likelihood factor given the others is below 1 (slam/pairing_likelihood.hpp): measured
  // 0.28 m, 0 spurious (the same as without smoother merges; 0.33 m with the leftover
  // joins). Bound: 1.5x the first measured ATE.
  const GraphRun r = RunGraphSlam(121);
  EXPECT_LT(r.ate, 0.42);
  EXPECT_LE(r.map.spurious + r.map.duplicates, 1);
}

/// Mean pose NEES (eval/consistency.hpp) over the trajectory entries with a usable covariance.
double Anees(const Estimate& e, const Stream& s) {
  std::map<double, SE2> gt;
  for (const auto& g : s.groundtruth) gt[g.t_s] = g.pose;
  double sum = 0.0;
  int n = 0;
  for (const auto& p : e.trajectory) {
    const auto it = gt.find(p.t_s);
    if (!p.has_covariance || it == gt.end()) continue;
    if (const double nees = PoseNees(it->second, p.pose, p.covariance); std::isfinite(nees)) sum += nees, ++n;
  }
  return sum / n;
}

TEST(ForestAccuracy, InvariantEkfHoldsTheHeadingWithKnownIds) {
  // ekf-slam with known ids, standard error against the invariant one (invariant=true,
  // slam/ekf_slam_filter.hpp). Measured (seeds 13, 14): standard 1.50 / 2.14 m, ANEES 3.7 /
  // 4.3; invariant 0.48 / 0.87 m, ANEES 2.3 / 2.4 (slambox sweep, slam/README_landmark_slam.md
  // "The Invariant EKF"). Bounds: 1.5x the invariant's measured ATE, ANEES below 3.3.
  const std::map<std::uint64_t, double> bound = {{13u, 0.72}, {14u, 1.31}};
  Scenario scenario = LoadScenario("forest");
  scenario.sensors.landmarks->known_ids = true;
  for (const auto& [seed, b] : bound) {
    const Stream s = Simulate(scenario, seed);
    const Estimate standard = Replay(*FindModule("ekf-slam").create({}), s);
    const Estimate invariant = Replay(*FindModule("ekf-slam").create({{"invariant", "true"}}), s);
    std::printf("seed %lu, known ids: ekf-slam %.2f m (ANEES %.2f), invariant %.2f m (ANEES %.2f)\n",
                static_cast<unsigned long>(seed), AteRmse(standard, s), Anees(standard, s), AteRmse(invariant, s),
                Anees(invariant, s));
    SCOPED_TRACE(seed);
    EXPECT_LT(AteRmse(invariant, s), b);
    EXPECT_LT(Anees(invariant, s), 3.3);
    EXPECT_GT(AteRmse(standard, s), b);  // what the invariant error fixes here
  }
}

}  // namespace
}  // namespace slambox
