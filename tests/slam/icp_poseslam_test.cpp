// icp-poseslam on a synthetic ring corridor (two laps, fixed seed): loop closures found
// and accepted, map and graph filled, accuracy far better than wheel odometry.
#include <gtest/gtest.h>

#include <cstdio>

#include "slam/dead_reckoning.hpp"
#include "slam/icp_odometry.hpp"
#include "slam/icp_poseslam.hpp"
#include "tests/slam/icp_module_support.hpp"

namespace slambox {
namespace {

TEST(IcpPoseSlam, AccurateOnTwoLapRingWithLoopClosures) {
  const Stream s = testing::RingStream(11, 2);
  const double odo = testing::PositionRmse(testing::RunModule(DeadReckoningModule(), s), s);
  const double icp_odo = testing::PositionRmse(testing::RunModule(IcpOdometryModule(), s), s);
  const Estimate est = testing::RunModule(IcpPoseSlamModule(), s);
  const double slam = testing::PositionRmse(est, s);
  int accepted = 0;
  for (const auto& lc : est.loop_closures) accepted += lc.accepted ? 1 : 0;
  std::printf("ring x2: odometry %.3f, icp-odometry %.3f, icp-poseslam %.3f m; loops %zu proposed %d accepted\n",
              odo, icp_odo, slam, est.loop_closures.size(), accepted);
  EXPECT_LT(slam, 0.05);
  EXPECT_LT(slam, odo / 10);
  EXPECT_GE(accepted, 5);
  ASSERT_EQ(est.trajectory.size(), s.groundtruth.size());
  EXPECT_FALSE(est.map_points.empty());
  ASSERT_TRUE(est.grid.has_value());
  EXPECT_GT(est.grid->width * est.grid->height, 0);
  EXPECT_GT(est.pose_graph.nodes.size(), 50u);
  EXPECT_EQ(est.pose_graph.node_t_s.size(), est.pose_graph.nodes.size());
  EXPECT_TRUE(est.diagnostics.count("loop_closures_accepted"));
}

}  // namespace
}  // namespace slambox
