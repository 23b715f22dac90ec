// mrpt-rbpf-slam in a room: deterministic for a seed; accuracy bounded near dead reckoning.
// Known issue (see slam/mrpt/README.md): with this configuration MRPT's particle weights
// stay nearly uniform (ESS/N ≈ 0.8-1), so the filter does not yet beat dead reckoning on
// this stream; the bounds below catch a regression (frame, time or conversion errors
// give metres of error, not centimetres).
#include <gtest/gtest.h>

#include "slam/mrpt/mrpt_rbpf_slam.hpp"
#include "tests/mrpt/mrpt_test_support.hpp"

namespace slambox::testing {
namespace {

const std::array<double, 4> kDriftyOdometry = {0.1, 0.01, 0.1, 0.01};

Estimate RunRbpf(const Stream& s, const ParamOverrides& overrides = {}) {
  auto module = MrptRbpfSlamModule().create(overrides);
  return Replay(*module, s);
}

TEST(MrptRbpfSlam, DeterministicForAStream) {
  const Stream s = LidarStream(4.0, 7, kDriftyOdometry);
  ExpectIdenticalTrajectories(RunRbpf(s), RunRbpf(s));
}

TEST(MrptRbpfSlam, StaysNearDeadReckoningAndMapsTheRoom) {
  const Stream s = LidarStream(4.0, 7, kDriftyOdometry);
  const Estimate e = RunRbpf(s);
  ASSERT_GT(e.trajectory.size(), 20u);
  const double rmse = Rmse(PositionErrors(e, s));
  const double dr = DeadReckoningRmse(e, s);
  EXPECT_LT(rmse, 2.0 * dr) << "rbpf " << rmse << " dead reckoning " << dr;  // measured 0.19 vs 0.13
  EXPECT_LT(rmse, 0.25);
  for (size_t k = 1; k < e.trajectory.size(); ++k) ASSERT_GT(e.trajectory[k].t_s, e.trajectory[k - 1].t_s);
  EXPECT_GT(e.map_points.size(), 100u);
  EXPECT_FALSE(e.diagnostics.at("neff").empty());
}

TEST(MrptRbpfSlam, ScanBeforeAnyOdometryIsAZeroMotionStep) {
  // The simulator emits a scan at t = 0: MRPT asserts an action, and the filter step it
  // runs there must not duplicate the start time in the trajectory.
  Stream s = LidarStream(4.0, 8, kDriftyOdometry);
  s.events.resize(200);  // a short prefix keeps this fast
  for (const auto& ev : s.events)
    if (const auto* scan = std::get_if<LaserScanEvent>(&ev)) {
      LaserScanEvent first = *scan;
      first.t_s = 0.0;
      s.events.insert(s.events.begin(), first);
      break;
    }
  const Estimate e = RunRbpf(s);
  ASSERT_GE(e.trajectory.size(), 2u);
  EXPECT_EQ(e.trajectory.front().t_s, 0.0);
  for (size_t k = 1; k < e.trajectory.size(); ++k) ASSERT_GT(e.trajectory[k].t_s, e.trajectory[k - 1].t_s);
  EXPECT_LT(Rmse(PositionErrors(e, s)), 0.25);  // measured 0.12 (dead reckoning 0.03): see the known issue
}

}  // namespace
}  // namespace slambox::testing
