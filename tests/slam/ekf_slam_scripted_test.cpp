// EKF-SLAM on scripted landmark streams (exact events, no simulator): the held pairings of
// an uncertain pose (a lone pairing never closes the loop, two landmarks in consecutive
// scans do) and the closure test's shared density of unmapped landmarks.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <string>
#include <variant>
#include <vector>

#include "slam/ekf_slam.hpp"

namespace slambox {
namespace {

Estimate RunEkf(const Stream& stream, const EkfSlamConfig& config = {}) {
  EkfSlam ekf(config);
  return Replay(ekf, stream);
}

/// A scripted run: landmarks `marks` seen together 3 times from the start (confirmed; or
/// `first_scans`, the indices each of the 3 scans sees), then
/// a 10 m out-and-back drive without scans (noise-free odometry, large alpha: the pose
/// covariance grows to ~1 m and ~8 deg while the mean stays exact), then the scans
/// `rescans` from the start pose again, each the indices into `marks` it sees (empty: a
/// scan that sees nothing), each at the time of an odometry event so the trajectory shows
/// its update.
Stream HoldStream(double clutter_per_scan, const std::vector<std::vector<int>>& rescans,
                  const std::vector<Eigen::Vector2d>& marks = {{5, 3}},
                  const std::vector<std::vector<int>>& first_scans = {}) {
  Stream s;
  s.header.sensors.odometry = OdometryConfig{.rate_hz = 50, .alpha = {0.001, 0.002, 0.05, 0.001}};
  s.header.sensors.landmarks = LandmarkSensorConfig{.rate_hz = 5, .range_max_m = 10, .fov_deg = 360,
                                                    .sigma_range_m = 0.05, .sigma_bearing_deg = 1.0,
                                                    .known_ids = false, .clutter_per_scan = clutter_per_scan};
  std::vector<LandmarkObservation> seen;
  for (const Eigen::Vector2d& m : marks) seen.push_back({m.norm(), std::atan2(m.y(), m.x()), -1});
  const auto observed = [&](const std::vector<int>& scan) {
    std::vector<LandmarkObservation> z;
    for (int m : scan) z.push_back(seen[m]);
    return z;
  };
  double t = 0.0;
  for (int k = 0; k < 3; ++k)
    s.events.push_back(LandmarkEvent{t += 0.2, first_scans.empty() ? seen : observed(first_scans.at(k))});
  for (int leg = 0; leg < 2; ++leg) {
    for (int k = 0; k < 20; ++k) s.events.push_back(OdometryEvent{t += 0.1, SE2(0.5, 0, 0)});
    s.events.push_back(OdometryEvent{t += 0.1, SE2(0, 0, M_PI - 1e-9)});
  }
  for (const std::vector<int>& scan : rescans) {
    s.events.push_back(OdometryEvent{t += 0.1, SE2(0, 0, 0)});
    s.events.push_back(LandmarkEvent{t, observed(scan)});
  }
  return s;
}

std::vector<double> Series(const Estimate& e, const std::string& name) {
  std::vector<double> v;
  for (const auto& [t, x] : e.diagnostics.at(name)) v.push_back(x);
  return v;
}

/// Trace of the pose covariance after each of the last n trajectory entries (the rescans).
std::vector<double> LastTraces(const Estimate& e, size_t n) {
  std::vector<double> v;
  for (size_t k = e.trajectory.size() - n; k < e.trajectory.size(); ++k) v.push_back(e.trajectory[k].covariance.trace());
  return v;
}

TEST(EkfSlam, LonePairingRepeatedInScansNeverClosesTheLoop) {
  // Pose sigma ~1 m, 8 deg: one fake (clutter, or a tree never mapped) in the gate is
  // likelier than a gate miss (mu ~ 0.05 > 0.01). A repeat of the one pairing is no
  // evidence against a tree that stays in the gate: held in every scan, never used.
  const Estimate e = RunEkf(HoldStream(1.0, {{0}, {0}, {0}, {0}, {0}, {0}}));
  const std::vector<double> held = Series(e, "held_pairings");
  ASSERT_EQ(held.size(), 9u);  // 3 scans at the start, 6 after the drive
  for (int k = 0; k < 3; ++k) EXPECT_EQ(held[k], 0.0) << k;  // the robot is certain at the start
  for (int k = 3; k < 9; ++k) EXPECT_EQ(held[k], 1.0) << k;
  const std::vector<double> trace = LastTraces(e, 6);
  EXPECT_GT(trace.front(), 1.0);
  EXPECT_DOUBLE_EQ(trace.back(), trace.front());  // never updated
  ASSERT_EQ(e.landmarks.size(), 1u);              // held is not missed: the landmark is not removed
}

TEST(EkfSlam, HeldPairingsOfTwoLandmarksInConsecutiveScansCloseTheLoop) {
  // Two landmarks, each alone in its scan: the second scan's pairing is a fake only if
  // both are (mu_1 mu_2 ~ 0.003 < 0.01): used. With hold_evidence=scans only a repeat of
  // the same pairing counts, and the second landmark's first pairing is held too.
  const std::vector<Eigen::Vector2d> marks = {{5, 3}, {5, -3}};
  for (const HoldEvidence evidence : {HoldEvidence::kDistinctLandmarks, HoldEvidence::kRepeatedScans}) {
    const bool by_landmarks = evidence == HoldEvidence::kDistinctLandmarks;
    const Estimate e = RunEkf(HoldStream(1.0, {{0}, {1}}, marks), {.hold_evidence = evidence});
    const std::vector<double> held = Series(e, "held_pairings");
    ASSERT_EQ(held.size(), 5u);
    EXPECT_EQ(held[3], 1.0) << by_landmarks;
    EXPECT_EQ(held[4], by_landmarks ? 0.0 : 1.0) << by_landmarks;
    const std::vector<double> trace = LastTraces(e, 2);
    EXPECT_GT(trace[0], 1.0);
    if (by_landmarks) EXPECT_LT(trace[1], 0.5 * trace[0]);  // used
    else EXPECT_DOUBLE_EQ(trace[1], trace[0]);
    ASSERT_EQ(e.landmarks.size(), 2u);
    EXPECT_NEAR(e.trajectory.back().pose.x, 0.0, 1e-6);
  }
}

TEST(EkfSlam, RepeatedScansOptionLetsALonePairingThroughOnItsSecondScan) {
  // hold_evidence=scans (the rule before): clutter is drawn anew each scan, mu^2 < 0.01.
  const Estimate e = RunEkf(HoldStream(1.0, {{0}, {0}, {0}, {0}}), {.hold_evidence = HoldEvidence::kRepeatedScans});
  const std::vector<double> held = Series(e, "held_pairings");
  ASSERT_EQ(held.size(), 7u);
  EXPECT_EQ(held[3], 1.0);
  EXPECT_EQ(held[4], 0.0);
  EXPECT_EQ(held[5], 0.0);
  const std::vector<double> trace = LastTraces(e, 4);
  EXPECT_GT(trace[0], 1.0);             // not used: as uncertain as after the drive
  EXPECT_LT(trace[1], 0.5 * trace[0]);  // used
  ASSERT_EQ(e.landmarks.size(), 1u);
  EXPECT_LT((e.landmarks[0].position - Eigen::Vector2d(5, 3)).norm(), 1e-6);
  EXPECT_NEAR(e.trajectory.back().pose.x, 0.0, 1e-6);
}

TEST(EkfSlam, HeldStreakEndsWithAScanThatDoesNotHoldIt) {
  for (const HoldEvidence evidence : {HoldEvidence::kDistinctLandmarks, HoldEvidence::kRepeatedScans}) {
    const Estimate e = RunEkf(HoldStream(1.0, {{0}, {}, {0}}), {.hold_evidence = evidence});
    const std::vector<double> held = Series(e, "held_pairings");
    ASSERT_EQ(held.size(), 6u);
    EXPECT_EQ(held[3], 1.0);
    EXPECT_EQ(held[4], 0.0);  // nothing seen
    EXPECT_EQ(held[5], 1.0);  // held again from the start, not used
  }
  // Landmarks: a scan that holds nothing ends the streak, so the second landmark is held.
  const Estimate e = RunEkf(HoldStream(1.0, {{0}, {}, {1}}, {{5, 3}, {5, -3}}));
  EXPECT_EQ(Series(e, "held_pairings")[5], 1.0);
}

TEST(EkfSlam, NoClutterOrDisabledHoldsNothing) {
  for (const auto& [clutter, hold] : std::vector<std::pair<double, bool>>{{0.0, true}, {1.0, false}}) {
    const Estimate e = RunEkf(HoldStream(clutter, {{0}}), {.hold_uncertain_pairings = hold});
    for (double h : Series(e, "held_pairings")) EXPECT_EQ(h, 0.0) << clutter;
    const double before = e.trajectory[e.trajectory.size() - 2].covariance.trace();
    EXPECT_LT(e.trajectory.back().covariance.trace(), 0.5 * before) << clutter;  // used at once
  }
}

/// A standing robot that sees one post alone, 5.83 m ahead, in `scans` consecutive scans
/// of a noisy detector with clutter (sigma 0.3 m / 2 deg, 1 fake per scan over a 120 deg,
/// 8 m footprint): each repeat's gate expects mu ~ 0.05 fakes, above the gate's miss 0.01.
Stream LonePostStream(int scans) {
  Stream s;
  s.header.sensors.odometry = OdometryConfig{.rate_hz = 50, .alpha = {0.001, 0.002, 0.001, 0.001}};
  s.header.sensors.landmarks = LandmarkSensorConfig{.rate_hz = 5, .range_max_m = 8, .fov_deg = 120,
                                                    .sigma_range_m = 0.3, .sigma_bearing_deg = 2.0,
                                                    .known_ids = false, .clutter_per_scan = 1.0};
  const Eigen::Vector2d post(5, 3);
  double t = 0.0;
  for (int k = 0; k < scans; ++k) {
    s.events.push_back(OdometryEvent{t += 0.2, SE2(0, 0, 0)});
    s.events.push_back(LandmarkEvent{t, {{post.norm(), std::atan2(post.y(), post.x()), -1}}});
  }
  return s;
}

TEST(EkfSlam, ALonePostsTrackIsConfirmedByItsOwnRepeats) {
  // hold_evidence=tracks: the post's track continues (the robot stands still), so its held
  // repeats count: held once (mu ~ 0.05), the next used (mu^2 < 0.01), which ends the
  // streak like a scan that holds nothing, and so on; the post is confirmed. landmarks: a
  // repeat is no evidence, every pairing is held and the post never becomes a landmark.
  const Stream stream = LonePostStream(8);
  const Estimate tracks = RunEkf(stream);
  EXPECT_EQ(Series(tracks, "held_pairings"), (std::vector<double>{0, 1, 0, 1, 0, 1, 0, 1}));
  ASSERT_EQ(tracks.landmarks.size(), 1u);
  EXPECT_LT((tracks.landmarks[0].position - Eigen::Vector2d(5, 3)).norm(), 1e-6);
  const Estimate landmarks = RunEkf(stream, {.hold_evidence = HoldEvidence::kDistinctLandmarks});
  EXPECT_EQ(Series(landmarks, "held_pairings"), (std::vector<double>{0, 1, 1, 1, 1, 1, 1, 1}));
  EXPECT_TRUE(landmarks.landmarks.empty());
}

TEST(EkfSlam, BothBranchesOfAClosureTestUseTheDensityAtTheFork) {
  // Ten posts mapped at the start (two in the first scan, eight more in the next: births
  // that make unmapped posts likely), the drive that leaves the pose uncertain, then scans
  // that see the first two again and two posts never seen before. The first two fall in
  // gates that may hold an unmapped post: the closure test forks. The branch without the
  // closure maps them anew, so it has more births; scored with its own births it would
  // call more detections new and find its scans likelier. Both use the density at the fork.
  std::vector<Eigen::Vector2d> marks = {{5, 3}, {5, -3}};
  for (int k = 0; k < 8; ++k) marks.push_back({-6.0, -7.0 + 2.0 * k});
  const int first_new = static_cast<int>(marks.size());
  for (int k = 0; k < 12; ++k) marks.push_back({2.0 + 0.5 * k, k % 2 ? 6.0 : -6.0});
  std::vector<std::vector<int>> rescans;
  for (int k = 0; k < 6; ++k) rescans.push_back({0, 1, first_new + 2 * k, first_new + 2 * k + 1});
  std::vector<int> all_first(first_new);
  std::iota(all_first.begin(), all_first.end(), 0);
  const Stream stream = HoldStream(0.01, rescans, marks, {{0, 1}, all_first, all_first});
  EkfSlam ekf({});
  ekf.Start(stream.header);
  int tested = 0, differing = 0;
  double fork_density = -1.0;
  for (const auto& event : stream.events) {
    if (const auto* o = std::get_if<OdometryEvent>(&event)) ekf.OnOdometry(*o);
    const auto* scan = std::get_if<LandmarkEvent>(&event);
    if (scan == nullptr) continue;
    ekf.OnLandmarks(*scan);
    const EkfSlam* rival = ekf.closure_rival();
    if (rival == nullptr) {
      fork_density = -1.0;
      continue;
    }
    if (fork_density < 0.0) fork_density = ekf.FakeDensity();
    ++tested;
    differing += rival->state().NumLandmarks() != ekf.state().NumLandmarks() ? 1 : 0;
    EXPECT_EQ(rival->FakeDensity(), ekf.FakeDensity()) << scan->t_s;
    EXPECT_EQ(ekf.FakeDensity(), fork_density) << scan->t_s;
  }
  EXPECT_GT(tested, 1);
  EXPECT_GT(differing, 0);  // the branches differ in their births
}

}  // namespace
}  // namespace slambox
