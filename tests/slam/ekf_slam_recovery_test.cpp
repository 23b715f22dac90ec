// EKF-SLAM's recovery of a scan that contradicts the predicted heading (unknown ids,
// slam/ekf_slam_recovery.cpp): an odometry that under-reports a fast turn, and with it its
// own variance, leaves every detection outside its gate.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/slam_module.hpp"
#include "slam/ekf_slam.hpp"

namespace slambox {
namespace {

constexpr double kDeg = M_PI / 180.0;

/// Eight posts 6-12 m around the origin, seen together from the origin in 5 scans (mapped
/// and confirmed), then a turn of 5 steps of `true_step_deg` that the odometry reports as
/// steps of `reported_step_deg` (alpha_1 = 0.2, so its variance follows the reported step),
/// then 5 scans from the turned pose, each at the time of a motionless odometry event.
Stream TurnStream(double true_step_deg, double reported_step_deg) {
  const std::vector<Eigen::Vector2d> posts = {{8, 1},   {6, 5},    {-2, 9},  {-7, 4},
                                              {-11, -3}, {-3, -8}, {4, -10}, {10, -6}};
  Stream s;
  s.header.sensors.odometry = OdometryConfig{.rate_hz = 50, .alpha = {0.2, 0.002, 0.05, 0.001}};
  s.header.sensors.landmarks = LandmarkSensorConfig{.rate_hz = 10, .range_max_m = 15, .fov_deg = 360,
                                                    .sigma_range_m = 0.05, .sigma_bearing_deg = 0.5,
                                                    .known_ids = false, .clutter_per_scan = 0.0};
  const auto scan_from = [&](double heading_rad) {
    std::vector<LandmarkObservation> z;
    for (const Eigen::Vector2d& p : posts) z.push_back({p.norm(), std::atan2(p.y(), p.x()) - heading_rad, -1});
    return z;
  };
  double t = 0.0;
  for (int k = 0; k < 5; ++k) s.events.push_back(LandmarkEvent{t += 0.1, scan_from(0.0)});
  for (int k = 0; k < 5; ++k) s.events.push_back(OdometryEvent{t += 0.02, SE2(0, 0, reported_step_deg * kDeg)});
  for (int k = 0; k < 5; ++k) {
    s.events.push_back(OdometryEvent{t += 0.1, SE2(0, 0, 0)});
    s.events.push_back(LandmarkEvent{t, scan_from(5 * true_step_deg * kDeg)});
  }
  return s;
}

Estimate RunEkf(const Stream& stream, bool recover) {
  EkfSlam ekf({.recover_heading = recover});
  return Replay(ekf, stream);
}

TEST(EkfSlamRecovery, AnUnderReportedTurnIsFoundUnderAWiderHeadingPrior) {
  // 10 deg turned, 2 deg reported: the predicted heading is 8 deg off at sigma ~0.4 deg.
  const Stream stream = TurnStream(2.0, 0.4);
  const Estimate on = RunEkf(stream, true);
  EXPECT_NEAR(on.trajectory.back().pose.theta / kDeg, 10.0, 0.2);
  EXPECT_EQ(on.landmarks.size(), 8u);  // no post mapped twice
  const auto& widened = on.diagnostics.at("heading_widened");
  ASSERT_EQ(widened.size(), 1u);      // the first scan after the turn, then the heading is known
  // Predicted sigma 0.4 deg (five steps of 0.2 (0.4 deg)^2): 8 deg is 20 sigma; widened 4x it
  // is still 5 sigma for the shared heading of eight pairings, 8x (3.2 deg) it is 2.5.
  EXPECT_EQ(widened[0].second, 8.0);
  // Without it the scans start landmarks at rotated positions and keep the heading wrong.
  const Estimate off = RunEkf(stream, false);
  EXPECT_GT(std::abs(off.trajectory.back().pose.theta / kDeg - 10.0), 5.0);
}

TEST(EkfSlamRecovery, AScanThatFitsItsPredictionIsLeftAlone) {
  // A turn reported as it was: every scan pairs at once, nothing is widened, and the
  // result is the same bit for bit with the recovery on or off.
  const Stream stream = TurnStream(2.0, 2.0);
  const Estimate on = RunEkf(stream, true), off = RunEkf(stream, false);
  EXPECT_EQ(on.diagnostics.count("heading_widened"), 0u);
  ASSERT_EQ(on.trajectory.size(), off.trajectory.size());
  for (size_t k = 0; k < on.trajectory.size(); ++k) EXPECT_EQ(on.trajectory[k].pose.theta, off.trajectory[k].pose.theta);
  EXPECT_NEAR(on.trajectory.back().pose.theta / kDeg, 10.0, 0.2);
}

TEST(EkfSlamRecovery, ATurnBeyondTheWidestPriorKeepsTheFirstAssociation) {
  // 60 deg turned, 5 reported (sigma 1 deg): 55 deg is beyond even 16 sigma; the search is recorded as failed (0).
  const Estimate e = RunEkf(TurnStream(12.0, 1.0), true);
  const auto& widened = e.diagnostics.at("heading_widened");
  ASSERT_FALSE(widened.empty());
  EXPECT_EQ(widened[0].second, 0.0);
}

}  // namespace
}  // namespace slambox
