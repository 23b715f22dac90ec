// Sweep summary cost: results.csv, timing.csv and summary.md for a 1000-run sweep
// (5 algorithms each). Target: < 2 s. Run: ./build/bench/sweep_summary_bench
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "app/sweep_spec.hpp"
#include "app/sweep_summary.hpp"
#include "core/atomic_file.hpp"

namespace {

namespace fs = std::filesystem;
using namespace slambox;

struct FakeSweep {
  std::string dir;
  SweepSpec spec;
  std::vector<SweepRun> runs;
};

// 10 scenarios x 10 grid points x 10 seeds, each run's metrics.json with 5 algorithms.
FakeSweep MakeFakeSweep() {
  FakeSweep f;
  f.dir = (fs::temp_directory_path() / ("slambox_summary_bench_" + std::to_string(getpid()))).string();
  for (int s = 0; s < 10; ++s) f.spec.scenarios.push_back("scenario" + std::to_string(s));
  f.spec.algorithms = {"odometry", "ekf-slam", "graphslam", "fastslam1", "fastslam2"};
  for (std::uint64_t seed = 0; seed < 10; ++seed) f.spec.seeds.push_back(seed);
  f.spec.grid = {{"sensors.odometry.rate_hz", {"10", "20", "30", "40", "50", "60", "70", "80", "90", "100"}}};
  f.runs = ExpandSweep(f.spec);
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0.01, 1.0);
  for (const auto& run : f.runs) {
    nlohmann::json doc = {{"scenario", run.scenario}, {"seed", run.seed}, {"algorithms", nlohmann::json::object()}};
    for (const auto& a : f.spec.algorithms) {
      nlohmann::json m = {{"status", "ok"}, {"runtime_s", u(rng)}, {"realtime_factor", 100 * u(rng)}};
      for (const char* k : {"ate_rmse_m", "ate_mean_m", "ate_max_m", "ate_aligned_rmse_m", "rpe_trans_rmse_m",
                            "rpe_rot_rmse_deg", "anees", "landmark_rmse_m", "heading_rmse_deg", "ate_median_m"})
        m[k] = u(rng);
      doc["algorithms"][a] = m;
    }
    WriteFileAtomic(f.dir + "/runs/" + run.id + "/metrics.json", doc.dump(1));
  }
  return f;
}

void BM_SweepSummary1000Runs(benchmark::State& state) {
  static const FakeSweep sweep = MakeFakeSweep();
  for (auto _ : state) WriteSweepSummary(sweep.dir, sweep.spec, sweep.runs);
  state.counters["runs"] = static_cast<double>(sweep.runs.size());
}
BENCHMARK(BM_SweepSummary1000Runs)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
