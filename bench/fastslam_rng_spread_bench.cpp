// How much of fastslam2's ATE on `landmarks` (known ids, seeds 0..9) is the luck of its own
// generator: each stream is replayed K times with different module seeds (the stream's
// header seed, which only the module's generator reads, is replaced by 1000 seed + k).
// Reports the mean single-run ATE, the ATE of the K runs' averaged positions, and the RMS
// spread of the runs about that average, against ekf-slam on the same streams.
//   ./build/bench/fastslam_rng_spread_bench   (per-seed lines on stderr)
// A depleted particle filter outputs one sample of the path posterior, so independent
// runs scatter around the posterior mean by about the posterior's own spread.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>

#include "sim/simulate.hpp"
#include "slam/ekf_slam.hpp"
#include "bench/trajectory_error.hpp"
#include "slam/fastslam.hpp"

namespace slambox {
namespace {

// Args: particles M, runs K.
void BM_RngSpread(benchmark::State& state) {
  const int particles = static_cast<int>(state.range(0)), runs = static_cast<int>(state.range(1));
  constexpr int kSeeds = 10;
  for (auto _ : state) {
    double ekf_sum = 0, single_sum = 0, average_sum = 0, spread_sum = 0;
    for (int seed = 0; seed < kSeeds; ++seed) {
      const Stream s = Simulate(LoadScenario("landmarks", {}), seed);
      EkfSlam ekf{EkfSlamConfig{}};
      const double ekf_ate = PositionRmse(Replay(ekf, s).trajectory, s);
      std::vector<std::vector<PoseEstimate>> paths;
      double single = 0;
      for (int k = 0; k < runs; ++k) {
        Stream copy = s;
        copy.header.seed = 1000 * static_cast<std::uint64_t>(seed) + k;
        FastSlam2Config c;
        c.particles = particles;
        FastSlam2 f{c};
        paths.push_back(Replay(f, copy).trajectory);
        single += PositionRmse(paths.back(), s) / runs;
      }
      std::vector<PoseEstimate> average = paths.front();
      double spread2 = 0;
      for (size_t i = 0; i < average.size(); ++i) {
        Eigen::Vector2d m = Eigen::Vector2d::Zero();
        for (const auto& p : paths) m += p[i].pose.translation() / runs;
        for (const auto& p : paths) spread2 += (p[i].pose.translation() - m).squaredNorm() / runs;
        average[i].pose = SE2(m.x(), m.y(), average[i].pose.theta);
      }
      const double spread = std::sqrt(spread2 / average.size()), avg_ate = PositionRmse(average, s);
      std::fprintf(stderr, "M %d K %d seed %d: ekf %.4f, fastslam2 single-run mean %.4f, averaged %.4f, spread %.4f\n",
                   particles, runs, seed, ekf_ate, single, avg_ate, spread);
      ekf_sum += ekf_ate, single_sum += single, average_sum += avg_ate, spread_sum += spread;
    }
    state.counters["ekf_ate_m"] = ekf_sum / kSeeds;
    state.counters["single_run_ate_m"] = single_sum / kSeeds;
    state.counters["averaged_ate_m"] = average_sum / kSeeds;
    state.counters["spread_m"] = spread_sum / kSeeds;
  }
}
BENCHMARK(BM_RngSpread)->ArgNames({"M", "K"})->Args({50, 8})->Args({200, 4})->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
}  // namespace slambox

BENCHMARK_MAIN();
