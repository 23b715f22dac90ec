// mrpt-icp-slam in a room: deterministic, better than dead reckoning, map on the walls.
#include <gtest/gtest.h>

#include "slam/mrpt/mrpt_icp_slam.hpp"
#include "tests/mrpt/mrpt_test_support.hpp"

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

TEST(MrptIcpSlam, BeatsDeadReckoningAndMapsTheWalls) {
  for (const std::string algorithm : {"classic", "lm"}) {
    const Stream s = LidarStream(6.0, 5, kDriftyOdometry);
    const Estimate e = RunIcp(s, {{"icp_algorithm", algorithm}});
    const double rmse = Rmse(PositionErrors(e, s));
    const double dr = DeadReckoningRmse(e, s);
    EXPECT_LT(rmse, 0.5 * dr) << algorithm << ": icp " << rmse << " dead reckoning " << dr;
    EXPECT_LT(rmse, 0.10) << algorithm;
    ASSERT_GT(e.map_points.size(), 100u);
    int near = 0;
    for (const auto& p : e.map_points) near += DistanceToWalls(p, s.header.world) < 0.10;
    EXPECT_GT(near, 0.95 * e.map_points.size()) << algorithm;
  }
}

}  // namespace
}  // namespace slambox::testing
