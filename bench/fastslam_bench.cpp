// FastSLAM speed and memory (issue 7): real-time factor with 100 particles and 1000
// landmarks at 10 Hz; live landmark-tree nodes against M and N (~ M log N, not M N);
// particle depletion (distinct ancestors of the first pose) over a long run.
//
// The world: N landmarks uniform at 0.025 / m^2 in a square; the robot (5 m/s) drives a
// lawnmower over it with lanes 30 m apart, so a 15 m sensor sees every landmark in one
// lap (~14 landmarks per scan). Two laps; the first builds the map (untimed), the second
// is timed (manual time = this thread's CPU time), so the map holds ~N landmarks while timed.
//   ./build/bench/fastslam_bench --benchmark_filter=RealTime
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <random>

#include "slam/fastslam.hpp"
#include "tests/support/synthetic_stream.hpp"

namespace slambox {
namespace {

Stream LawnmowerStream(int n_landmarks, bool known_ids, int laps, std::uint64_t seed) {
  const double side_m = std::sqrt(n_landmarks / 0.025);
  World world;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, side_m);
  for (int i = 0; i < n_landmarks; ++i) world.landmarks.push_back({i, {u(rng), u(rng)}, 0.1});
  testing::SyntheticOptions o;
  o.path.clear();
  bool left_to_right = true;
  for (double y = 15.0; y < side_m; y += 30.0, left_to_right = !left_to_right) {
    o.path.emplace_back(left_to_right ? 5.0 : side_m - 5.0, y);
    o.path.emplace_back(left_to_right ? side_m - 5.0 : 5.0, y);
  }
  o.laps = laps;
  o.speed_mps = 5.0;
  o.seed = seed;
  o.sensors.odometry = OdometryConfig{};
  o.sensors.landmarks = LandmarkSensorConfig{.range_max_m = 15.0, .known_ids = known_ids};
  return testing::MakeSyntheticStream(o, world);
}

void Feed(FastSlam& f, const SensorEvent& ev) {
  if (auto* od = std::get_if<OdometryEvent>(&ev)) f.OnOdometry(*od);
  else if (auto* lm = std::get_if<LandmarkEvent>(&ev)) f.OnLandmarks(*lm);
}

// CPU time of this thread [s]: the machine is shared, so wall time overstates the cost.
double ThreadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

struct Run {
  double cpu_s = 0.0;        // second lap
  double wall_s = 0.0;       // second lap
  double simulated_s = 0.0;  // second lap
  int scans = 0;
};

Run RunTwoLaps(FastSlam& f, const Stream& s) {
  f.Start(s.header);
  const double lap_s = 0.5 * s.header.duration_s;
  Run r;
  std::chrono::steady_clock::time_point t0;
  double cpu0 = 0.0;
  bool timing = false;
  for (const SensorEvent& ev : s.events) {
    if (!timing && EventTime(ev) > lap_s) t0 = std::chrono::steady_clock::now(), cpu0 = ThreadCpuSeconds(), timing = true;
    Feed(f, ev);
    r.scans += timing && std::holds_alternative<LandmarkEvent>(ev);
  }
  r.cpu_s = ThreadCpuSeconds() - cpu0;
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.simulated_s = s.header.duration_s - lap_s;
  return r;
}

// Args: fastslam2 (0/1), particles M, landmarks N, known ids (0/1).
void BM_RealTime(benchmark::State& state) {
  const bool fs2 = state.range(0), known = state.range(3);
  const Stream s = LawnmowerStream(static_cast<int>(state.range(2)), known, 2, 7);
  for (auto _ : state) {
    FastSlamConfig c;
    c.particles = static_cast<int>(state.range(1));
    c.snapshot_period_s = 0;
    FastSlam f(c, fs2);
    const Run r = RunTwoLaps(f, s);
    state.SetIterationTime(r.cpu_s);
    state.counters["realtime_factor"] = r.simulated_s / r.cpu_s;  // simulated time / CPU time
    state.counters["realtime_factor_wall"] = r.simulated_s / r.wall_s;
    state.counters["ms_per_scan"] = 1e3 * r.cpu_s / r.scans;  // incl. the 5 odometry events per scan
    state.counters["map_size"] = f.particles().front().map.size;
  }
}
BENCHMARK(BM_RealTime)
    ->ArgNames({"fastslam2", "M", "N", "known_ids"})
    ->Args({0, 100, 1000, 1})
    ->Args({0, 100, 1000, 0})
    ->Args({1, 100, 1000, 1})
    ->Args({1, 100, 1000, 0})
    ->Args({1, 50, 1000, 1})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

// Live tree nodes, sampled every 5 s of the second lap (known ids, fastslam1), against
// what M independent maps would hold (M x one map). With path copying, live = one map
// (~2N nodes) + the nodes written since the particles' lineages last shared them
// ~ 2N + c M log2 N, so "extra_per_M_log2N" stays flat as M and N grow, and
// "live_over_full" falls as 1/M.
void BM_Memory(benchmark::State& state) {
  const int M = static_cast<int>(state.range(0)), N = static_cast<int>(state.range(1));
  const Stream s = LawnmowerStream(N, true, 2, 7);
  for (auto _ : state) {
    FastSlamConfig c;
    c.particles = M;
    c.snapshot_period_s = 5.0;
    FastSlam f(c, false);
    const double cpu0 = ThreadCpuSeconds();
    const Estimate e = Replay(f, s);
    state.SetIterationTime(ThreadCpuSeconds() - cpu0);
    double live = 0.0, samples = 0.0, one_map = 0.0;
    for (const auto& [t, nodes] : e.diagnostics.at("map_tree_nodes"))
      if (t > 0.5 * s.header.duration_s) live += nodes, samples += 1;
    live /= samples;
    for (const FastSlamParticle& p : f.particles())
      one_map = std::max(one_map, static_cast<double>(CountDistinctNodes({&p.map})));
    state.counters["live_nodes"] = live;
    state.counters["one_map_nodes"] = one_map;
    state.counters["live_over_full"] = live / (M * one_map);
    state.counters["extra_per_M_log2N"] = (live - one_map) / (M * std::log2(static_cast<double>(N)));
  }
}
BENCHMARK(BM_Memory)
    ->ArgNames({"M", "N"})
    ->Args({25, 1000})
    ->Args({50, 1000})
    ->Args({100, 1000})
    ->Args({200, 1000})
    ->Args({100, 250})
    ->Args({100, 500})
    ->Args({100, 2000})
    ->UseManualTime()
    ->Iterations(1)
    ->Unit(benchmark::kSecond);

// Particle depletion (Bailey et al. 2006): distinct ancestors of the first pose at the
// end of each quarter of a 4-lap run (N = 250, M = 100, known ids).
void BM_Degeneracy(benchmark::State& state) {
  const bool fs2 = state.range(0);
  const Stream s = LawnmowerStream(250, true, 4, 7);
  for (auto _ : state) {
    FastSlamConfig c;
    c.snapshot_period_s = 0;
    FastSlam f(c, fs2);
    const Estimate e = Replay(f, s);
    const auto& series = e.diagnostics.at("distinct_ancestors");
    for (int q = 1; q <= 4; ++q) {
      const size_t i = std::min(series.size() - 1, q * series.size() / 4);
      state.counters["ancestors_q" + std::to_string(q)] = series[i].second;
    }
    double first_single_s = -1;  // first time all particles descend from one initial particle
    for (const auto& [t, a] : series)
      if (a == 1 && first_single_s < 0) first_single_s = t;
    state.counters["t_one_ancestor_s"] = first_single_s;
    state.counters["ancestors_t10s"] = series[std::min(series.size() - 1, size_t{100})].second;  // 10 Hz scans
    double resamplings = 0;
    for (const auto& [t, r] : e.diagnostics.at("resampled")) resamplings += r;
    state.counters["resamplings"] = resamplings;
    state.counters["duration_s"] = s.header.duration_s;
  }
}
BENCHMARK(BM_Degeneracy)->ArgNames({"fastslam2"})->Arg(0)->Arg(1)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
}  // namespace slambox

BENCHMARK_MAIN();
