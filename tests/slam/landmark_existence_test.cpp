// The sequential existence test (slam/landmark_existence.hpp): Wald's bounds and the
// trials' log likelihood ratios against hand-computed values, and ekf-slam's tentative
// and confirmed landmarks on scripted detections with exact counts under the rule.
#include "slam/landmark_existence.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "slam/ekf_slam.hpp"

namespace slambox {
namespace {

TEST(LandmarkExistence, WaldBoundsAndTrialsMatchHandComputation) {
  const WaldThresholds w = MakeWaldThresholds(0.01, 0.01);
  EXPECT_NEAR(w.log_confirm, std::log(99.0), 1e-12);  // log((1 - b) / a)
  EXPECT_NEAR(w.log_delete, -std::log(99.0), 1e-12);  // log(b / (1 - a))
  const WaldThresholds v = MakeWaldThresholds(0.001, 0.1);
  EXPECT_NEAR(v.log_confirm, std::log(0.9 / 0.001), 1e-12);
  EXPECT_NEAR(v.log_delete, std::log(0.1 / 0.999), 1e-12);
  // P_D 0.9, P_G 0.99, mu 0.05: detected log(0.891 / (1 - e^-0.05)), missed log(0.109 / e^-0.05).
  EXPECT_NEAR(DetectedLogRatio(0.9, 0.99, 0.05), std::log(0.891 / (1.0 - std::exp(-0.05))), 1e-12);
  EXPECT_NEAR(MissedLogRatio(0.9, 0.99, 0.05), std::log(0.109) + 0.05, 1e-12);
  // No clutter: a pairing cannot come from a phantom (clamped, finite); a miss is evidence only through P_D.
  EXPECT_EQ(DetectedLogRatio(0.4, 0.99, 0.0), kMaxTrialLogRatio);
  EXPECT_NEAR(MissedLogRatio(0.4, 0.99, 0.0), std::log(1.0 - 0.396), 1e-12);
  // A detector that never misses, with a gate that always holds it: a miss is impossible for a real landmark.
  EXPECT_EQ(MissedLogRatio(1.0, 1.0, 0.01), -kMaxTrialLogRatio);
  EXPECT_EQ(DetectedLogRatio(0.0, 0.99, 0.0), 0.0);  // neither hypothesis explains it: no evidence
}

/// A robot standing at the origin (pose known exactly), detector 10 m, 360 deg, sigma
/// 0.1 m / 1 deg, P_D 0.9, `clutter_per_scan` configured; one landmark at (5, 3), seen or
/// not in each scan of `script`.
Stream ScriptedStream(double clutter_per_scan, const std::vector<bool>& script) {
  Stream s;
  s.header.sensors.odometry = OdometryConfig{.rate_hz = 5, .alpha = {0.01, 0.01, 0.01, 0.01}};
  s.header.sensors.landmarks = LandmarkSensorConfig{.rate_hz = 5, .range_max_m = 10, .fov_deg = 360,
                                                    .sigma_range_m = 0.1, .sigma_bearing_deg = 1.0, .known_ids = false,
                                                    .detection_prob = 0.9, .clutter_per_scan = clutter_per_scan};
  const LandmarkObservation seen{std::hypot(5.0, 3.0), std::atan2(3.0, 5.0), -1};
  double t = 0.0;
  for (bool see : script)
    s.events.push_back(LandmarkEvent{t += 0.2, see ? std::vector<LandmarkObservation>{seen} : std::vector<LandmarkObservation>{}});
  return s;
}

struct Counts {
  std::vector<double> confirmed, tentative;  ///< per scan
  std::vector<double> log_ratio;             ///< per scan, of the first landmark (NaN once it is gone)
};
Counts RunScript(const Stream& s, const EkfSlamConfig& config) {
  EkfSlam ekf(config);
  ekf.Start(s.header);
  Counts c;
  for (const auto& event : s.events) {
    ekf.OnLandmarks(std::get<LandmarkEvent>(event));
    const auto& tracks = ekf.tracks();
    c.confirmed.push_back(static_cast<double>(std::count_if(tracks.begin(), tracks.end(), [](const auto& t) { return t.confirmed; })));
    c.tentative.push_back(static_cast<double>(tracks.size()) - c.confirmed.back());
    c.log_ratio.push_back(!tracks.empty() && tracks[0].key == 0 ? tracks[0].log_ratio : std::nan(""));
  }
  return c;
}

const EkfSlamConfig kSprt{.tentative_existence = ExistenceRule::kSequentialTest, .hold_uncertain_pairings = false};

TEST(LandmarkExistence, WithoutClutterOneResightingConfirms) {
  // Birth: 1 detection, 0 expected clutter: prior odds (1 + 1) / (0 + 1) = 2, log 0.69.
  // The re-sighting cannot be clutter: +50 >= log 99 -> confirmed at the 2nd sighting.
  const Counts c = RunScript(ScriptedStream(0.0, {true, true}), kSprt);
  EXPECT_EQ(c.confirmed, (std::vector<double>{0, 1}));
  // The count rule needs confirm_sightings = 3.
  const Counts old = RunScript(ScriptedStream(0.0, {true, true, true}), {.tentative_existence = ExistenceRule::kCounts, .confirmed_existence = ExistenceRule::kCounts});
  EXPECT_EQ(old.confirmed, (std::vector<double>{0, 0, 1}));
}

TEST(LandmarkExistence, TentativeIsDeletedAtTheThirdMiss) {
  // log 2 + k log(1 - 0.9 * 0.99): k = 2 -> -3.74 (kept), k = 3 -> -5.96 <= -log 99 = -4.60 (deleted).
  const Counts c = RunScript(ScriptedStream(0.0, {true, false, false, false}), kSprt);
  EXPECT_EQ(c.tentative, (std::vector<double>{1, 1, 1, 0}));
  EXPECT_EQ(c.confirmed, (std::vector<double>{0, 0, 0, 0}));
}

TEST(LandmarkExistence, ClutterInTheGateMakesConfirmationSlower) {
  // 20 clutter per scan over 100 pi m^2: 0.064 / m^2. The birth's gate (S ~ 2R) holds
  // mu = 0.064 * pi * 9.21 * 2 * 0.1 * 0.01745 * 5.83 = 0.0375: prior odds clamped to
  // 1 / (1 + 2) (more births expected from clutter than seen), log -0.69; the 2nd
  // sighting adds log(0.891 / 0.0368) = 3.19 (2.49 < 4.60), the 3rd (S ~ 1.5 R) 3.47: confirmed.
  const Counts c = RunScript(ScriptedStream(20.0, {true, true, true}), kSprt);
  EXPECT_EQ(c.confirmed, (std::vector<double>{0, 0, 1}));
  // Without clutter the same script confirms at the 2nd sighting (above).
}

TEST(LandmarkExistence, ConfirmedLandmarkGoesWhenItsMissesOutweighItsSightings) {
  // Clutter 20 / scan, 4 sightings: -0.69 + 3.19 + 3.47 + 3.58 = 9.55 with the measured
  // P_D (0.9, the prior, in all three trials: the test above's gate, shrinking with each
  // update); with P_D = 1 (no rate estimate) 3 log(1 / 0.9) = 0.32 more, 9.87. Each miss
  // then adds log(1 - 0.99) + mu = -4.59: 3 misses leave -3.9 (kept), the 4th -8.5 <= -4.60.
  std::vector<bool> script = {true, true, true, true};
  for (int k = 0; k < 12; ++k) script.push_back(false);
  const Counts fixed = RunScript(ScriptedStream(20.0, script), {.hold_uncertain_pairings = false, .estimate_detection_rate = false});
  EXPECT_NEAR(fixed.log_ratio[3], 9.87, 0.01);
  EXPECT_EQ(fixed.confirmed, (std::vector<double>{0, 0, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0}));
  EXPECT_EQ(fixed.tentative.back(), 0.0);
  // With the measured rate, the first miss costs log(1 - 0.95 * 0.99) + mu (the band's
  // rate (1 + 0.9) / (1 + 1) after one counted sighting); as this landmark is the band's
  // only one, its misses lower the rate and each costs less: 12 misses keep it.
  const Counts measured = RunScript(ScriptedStream(20.0, script), kSprt);
  EXPECT_NEAR(measured.log_ratio[3], 9.55, 0.01);
  EXPECT_NEAR(measured.log_ratio[4], 9.55 + std::log(1.0 - 0.95 * 0.99), 0.05);
  for (size_t k = 5; k < script.size(); ++k) {
    EXPECT_LT(measured.log_ratio[k], measured.log_ratio[k - 1]) << k;
    EXPECT_GT(measured.log_ratio[k] - measured.log_ratio[k - 1], measured.log_ratio[k - 1] - measured.log_ratio[k - 2]) << k;
  }
  EXPECT_EQ(measured.confirmed.back(), 1.0);
}

TEST(LandmarkExistence, ClutterOnlyStreamConfirmsNothing) {
  // 2 false detections per scan (Poisson), uniform over the 10 m disc the sensor
  // covers, as configured; 1000 scans. Every phantom starts at ever smaller prior odds
  // and must then reappear in its gate against mu ~ 0.004 per scan.
  Stream s = ScriptedStream(2.0, std::vector<bool>(1000, false));
  std::mt19937_64 rng(14);
  std::poisson_distribution<int> count(2.0);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (auto& e : s.events)
    for (int k = count(rng); k > 0; --k)
      std::get<LandmarkEvent>(e).observations.push_back({10.0 * std::sqrt(u(rng)), M_PI * (2 * u(rng) - 1), -1});
  // The default (sequential test, held pairings), the test alone, and the count rule.
  for (const EkfSlamConfig& config : {EkfSlamConfig{}, kSprt, EkfSlamConfig{.tentative_existence = ExistenceRule::kCounts}}) {
    const Counts c = RunScript(s, config);
    double most = 0, early = 0, late = 0;
    for (double n : c.confirmed) most = std::max(most, n);
    for (size_t k = 100; k < 500; ++k) early += c.tentative[k] / 400.0;
    for (size_t k = 500; k < 1000; ++k) late += c.tentative[k] / 500.0;
    EXPECT_EQ(most, 0.0) << NameOf(ExistenceRuleNames(), config.tentative_existence);
    EXPECT_GT(early, 0.5);            // phantoms are created ...
    EXPECT_LT(late, 1.25 * early);    // ... and deleted: the state does not grow
    std::printf("%s: tentative landmarks, mean over scans 100-499 %.2f, 500-999 %.2f\n",
                NameOf(ExistenceRuleNames(), config.tentative_existence), early, late);
  }
}

}  // namespace
}  // namespace slambox
