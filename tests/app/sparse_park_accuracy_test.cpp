// ekf-slam and graphslam on a sparse park where one update must carry a correction of many
// sigmas: the held-out random park lm20_10 (scripts/random_scenarios.py, batch 20; 12 posts in
// 110 x 58 m, a 90 deg detector with a precise range and a 3 deg bearing, known ids, a figure
// eight driven three times). Seed 0 re-sights a post at 252 s after a long drift: linearized at the prior,
// that update turned the heading from -14 to -128 deg off and the filter never recovered.
// With the relinearized update (relinearize_step_prob, slam/ekf_slam_filter.hpp) it holds.
// Measured at commit time (ATE RMSE): seed 0 4.774 m, seed 2 5.406 m (relinearize_step_prob=0:
// 62.11 / 26.11 m; dead reckoning 11.80 / 23.18 m); bounds 1.5x, and the premise is checked:
// without the relinearized update the filter is worse than dead reckoning on both.
#include <gtest/gtest.h>

#include <cstdio>

#include "app/registry.hpp"
#include "app/run_modules.hpp"
#include "sim/simulate.hpp"

namespace slambox {
namespace {

constexpr const char* kPark = R"yaml(version: 1
name: lm20_10
description: "random landmark park (eight, 110 x 58 m, 12 posts)"
world:
  walls:
    - polygon: [[0, 0], [110.00, 0], [110.00, 58.15], [0, 58.15]]
  landmarks:
    - {pos: [91.85, 12.99], radius_m: 0.15}
    - {pos: [6.60, 8.20], radius_m: 0.15}
    - {pos: [92.56, 45.62], radius_m: 0.15}
    - {pos: [89.93, 23.34], radius_m: 0.15}
    - {pos: [13.39, 21.74], radius_m: 0.15}
    - {pos: [100.01, 34.69], radius_m: 0.15}
    - {pos: [75.42, 32.24], radius_m: 0.15}
    - {pos: [68.53, 44.94], radius_m: 0.15}
    - {pos: [22.54, 26.43], radius_m: 0.15}
    - {pos: [2.46, 48.45], radius_m: 0.15}
    - {pos: [48.56, 11.57], radius_m: 0.15}
    - {pos: [79.73, 10.87], radius_m: 0.15}
robot:
  start: {x: 5, y: 5, theta_deg: 0.0}
  path: [[55.0, 5], [55.0, 53.15], [105.0, 53.15], [105.0, 5], [55.0, 5], [55.0, 53.15], [5, 53.15], [5, 5]]
  laps: 3
sensors:
  odometry: {rate_hz: 50, alpha: [0.02, 0.005, 0.02, 0.005]}
  landmarks: {rate_hz: 10, range_max_m: 12, fov_deg: 90, sigma_range_m: 0.02, sigma_bearing_deg: 3.0, known_ids: true, detection_prob: 0.95, clutter_per_scan: 0}
)yaml";

double Ate(const char* algo, const Stream& stream, const ParamOverrides& params) {
  auto module = FindModule(algo).create(params);
  const ModuleRun run = ReplayAndScore(*module, stream, RunEvalOptions(stream, ""));
  EXPECT_EQ(run.metrics.status, RunStatus::kOk) << run.metrics.reason;
  return run.metrics.ate.rmse;
}

struct Expected {
  std::uint64_t seed;
  double ekf_ate_m;
  double odometry_ate_m;
};

class SparsePark : public ::testing::TestWithParam<Expected> {};

TEST_P(SparsePark, EkfCarriesAnUpdateOfManySigmas) {
  const Expected& want = GetParam();
  const Stream stream = Simulate(LoadScenarioText(kPark, "lm20_10"), want.seed);
  const double with = Ate("ekf-slam", stream, {});
  const double without = Ate("ekf-slam", stream, {{"relinearize_step_prob", "0"}});
  std::printf("lm20_10 seed %llu: ekf-slam %.4g m, without the relinearized update %.4g m\n",
              static_cast<unsigned long long>(want.seed), with, without);
  EXPECT_LT(with, 1.5 * want.ekf_ate_m);
  EXPECT_GT(without, want.odometry_ate_m) << "the premise: the plain EKF loses this park";
}

INSTANTIATE_TEST_SUITE_P(Seeds, SparsePark,
                         ::testing::Values(Expected{0, 4.774, 11.80}, Expected{2, 5.406, 23.18}));

TEST(SparsePark, GraphSlamEndSolveOutOfTheFrontEndsJump) {
  // graphslam's front end is the same EKF, relinearized update included; its end solve
  // composes the replayed graph's keyframes with the odometry where the front end jumped
  // (frontend_jump_prob, slam/growth_replay.hpp). Measured at commit time: 1.906 m (before
  // the forty-second session, with the front end's update linearized at the prior: 64.00 m,
  // dead reckoning 11.80 m).
  const Stream stream = Simulate(LoadScenarioText(kPark, "lm20_10"), 0);
  const double ate = Ate("graphslam", stream, {});
  std::printf("lm20_10 seed 0: graphslam %.4g m\n", ate);
  EXPECT_LT(ate, 1.5 * 1.906);
}

}  // namespace
}  // namespace slambox
