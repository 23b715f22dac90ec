// mrpt-icp-slam in a room: deterministic, better than dead reckoning, map on the walls.
#include <gtest/gtest.h>

#include "slam/mrpt/mrpt_icp_slam.hpp"
#include "tests/mrpt/mrpt_test_support.hpp"
#include "tests/support/accuracy_bound.hpp"

#include <cstdio>

namespace slambox::testing {
namespace {

const std::array<double, 4> kDriftyOdometry = {0.1, 0.01, 0.1, 0.01};

Estimate RunIcp(const Stream& s, const ParamOverrides& overrides = {}) {
  auto module = MrptIcpSlamModule().create(overrides);
  return Replay(*module, s);
}

double DistanceToWalls(const Eigen::Vector2d& p, const World& w) {
  double best = 1e9;
  for (const auto& seg : w.wall_segments) {
    const Eigen::Vector2d d = seg.b - seg.a;
    const double u = std::clamp((p - seg.a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (seg.a + u * d - p).norm());
  }
  return best;
}

TEST(MrptIcpSlam, DeterministicForAStream) {
  const Stream s = LidarStream(6.0, 5, kDriftyOdometry);
  ExpectIdenticalTrajectories(RunIcp(s), RunIcp(s));
}

// Position RMSE [m] in the room (seed 5) with the classic and LM ICP; the test prints them:
// ./build/tests/mrpt_icp_slam_test --gtest_filter=MrptIcpSlam.BeatsDeadReckoning*
constexpr double kRoomRmse_m[] = {0.0199, 0.0488};

TEST(MrptIcpSlam, BeatsDeadReckoningAndMapsTheWalls) {
  const std::string algorithms[] = {"classic", "lm"};
  for (int i = 0; i < 2; ++i) {
    const std::string& algorithm = algorithms[i];
    const Stream s = LidarStream(6.0, 5, kDriftyOdometry);
    const Estimate e = RunIcp(s, {{"icp_algorithm", algorithm}});
    const double rmse = Rmse(PositionErrors(e, s));
    const double dr = DeadReckoningRmse(e, s);
    EXPECT_LT(rmse, 0.5 * dr) << algorithm << ": icp " << rmse << " dead reckoning " << dr;
    std::printf("mrpt-icp-slam %s: %.4f m (dead reckoning %.3f m)\n", algorithm.c_str(), rmse, dr);
    EXPECT_TRUE(NoWorseThanMeasured(rmse, kRoomRmse_m[i])) << algorithm;
    ASSERT_GT(e.map_points.size(), 100u);
    int near = 0;
    for (const auto& p : e.map_points) near += DistanceToWalls(p, s.header.world) < 0.10;
    EXPECT_GT(near, 0.95 * e.map_points.size()) << algorithm;
  }
}

}  // namespace
}  // namespace slambox::testing
