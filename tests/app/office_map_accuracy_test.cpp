// The built-in `office` (its world the ROS map image scenarios/maps/office_map.pgm): the
// LIDAR modules run in a world made of grid cells and keep the accuracy measured on it.
// Bounds are 1.5x the fixed-seed values (measured at commit time, printed on failure):
//   seed 0: icp-poseslam 0.00654, mcl 0.0151, icp-localization 0.00618, odometry 0.614 m
//   seed 1: icp-poseslam 0.00845, mcl 0.0155, icp-localization 0.00601, odometry 2.99 m
#include <gtest/gtest.h>

#include <map>

#include "app/registry.hpp"
#include "app/run_modules.hpp"
#include "sim/simulate.hpp"

namespace slambox {
namespace {

struct Expected {
  std::uint64_t seed;
  std::map<std::string, double> ate_rmse_m;
};

class OfficeMap : public ::testing::TestWithParam<Expected> {};

TEST_P(OfficeMap, LidarModulesStayAccurateInTheMapWorld) {
  const Expected& want = GetParam();
  const Stream stream = Simulate(LoadScenario("office"), want.seed);
  const EvalOptions options = RunEvalOptions(stream, "");
  for (const auto& [name, value] : want.ate_rmse_m) {
    auto module = FindModule(name).create({});
    const ModuleRun run = ReplayAndScore(*module, stream, options);
    ASSERT_EQ(run.metrics.status, RunStatus::kOk) << name << ": " << run.metrics.reason;
    const double ate = run.metrics.ate.rmse;
    std::printf("office seed %llu %s: ate_rmse_m %.6g\n", static_cast<unsigned long long>(want.seed), name.c_str(), ate);
    if (name == "odometry") EXPECT_NEAR(ate, value, 0.01 * value) << "dead reckoning is deterministic: " << ate;
    else EXPECT_LT(ate, 1.5 * value) << name << " seed " << want.seed << ": " << ate;
  }
}

INSTANTIATE_TEST_SUITE_P(Seeds, OfficeMap,
                         ::testing::Values(Expected{0, {{"odometry", 0.614173}, {"icp-poseslam", 0.00653916},
                                                        {"mcl", 0.0151068}, {"icp-localization", 0.00617924}}},
                                           Expected{1, {{"odometry", 2.99247}, {"icp-poseslam", 0.00845252},
                                                        {"mcl", 0.0154987}, {"icp-localization", 0.00600529}}}));

}  // namespace
}  // namespace slambox
