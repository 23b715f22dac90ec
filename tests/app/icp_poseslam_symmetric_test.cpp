// icp-poseslam on the built-in `symmetric` scenario (a room whose halves look alike):
// with the default configuration (correlative loop search in an uncertainty window,
// ambiguity and ICP verification) no accepted closure is false, closures are found, and
// the trajectory stays accurate. False = the measured relative pose is > 1 m from the true one.
#include <gtest/gtest.h>

#include <map>

#include "sim/scenario.hpp"
#include "sim/simulate.hpp"
#include "slam/icp_poseslam.hpp"

namespace slambox {
namespace {

TEST(IcpPoseSlamSymmetric, NoFalseClosuresAccepted) {
  const Scenario scenario = LoadScenario("symmetric");
  for (std::uint64_t seed : {0u, 3u}) {
    const Stream s = Simulate(scenario, seed);
    auto module = IcpPoseSlamModule().create({});
    const Estimate e = Replay(*module, s);
    std::map<double, SE2> gt;
    for (const auto& g : s.groundtruth) gt[g.t_s] = g.pose;
    int accepted = 0, wrong = 0;
    for (const auto& lc : e.loop_closures) {
      if (!lc.accepted) continue;
      ++accepted;
      const SE2 truth = Between(gt.at(lc.t_from_s), gt.at(lc.t_to_s));
      wrong += (truth.translation() - lc.T_from_to.translation()).norm() > 1.0 ? 1 : 0;
    }
    EXPECT_EQ(wrong, 0) << "seed " << seed;
    EXPECT_GT(accepted, 50) << "seed " << seed;  // 110-112 on seeds 0..9 (icp_scenarios_bench)
    double sum = 0;
    int n = 0;
    for (const auto& p : e.trajectory)
      if (auto it = gt.find(p.t_s); it != gt.end()) sum += (p.pose.translation() - it->second.translation()).squaredNorm(), ++n;
    ASSERT_GT(n, 100);
    EXPECT_LT(std::sqrt(sum / n), 0.03) << "seed " << seed;  // 0.006-0.015 m on seeds 0..9
  }
}

}  // namespace
}  // namespace slambox
