// Simulator speed: simulated seconds per wall second for each built-in scenario
// (counter realtime_factor), and LIDAR rays per second through the grid index versus
// b2World::RayCast. Run: ./build/bench/sim_bench
#include <benchmark/benchmark.h>

#include <random>

#include "sim/box2d_world.hpp"
#include "sim/ray_caster.hpp"
#include "sim/scenario.hpp"
#include "sim/simulate.hpp"

namespace slambox {
namespace {

void BM_Simulate(benchmark::State& state, const std::string& name) {
  const Scenario scenario = LoadScenario(name);
  double simulated_s = 0.0;
  for (auto _ : state) {
    const Stream stream = Simulate(scenario, 0);
    simulated_s += stream.header.duration_s;
    benchmark::DoNotOptimize(stream.events.data());
  }
  state.counters["realtime_factor"] = benchmark::Counter(simulated_s, benchmark::Counter::kIsRate);
}

/// Rays from poses along the loop scenario's corridors, in all directions.
struct RaySet {
  std::vector<Eigen::Vector2d> origins, dirs;
};
RaySet LoopRays(const Scenario& s) {
  RaySet r;
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0), ang(-M_PI, M_PI);
  const auto& path = s.robot.path;
  for (int i = 0; i < 4096; ++i) {
    const size_t k = rng() % (path.size() - 1);
    r.origins.push_back(path[k] + u(rng) * (path[k + 1] - path[k]));
    const double a = ang(rng);
    r.dirs.emplace_back(std::cos(a), std::sin(a));
  }
  return r;
}

void BM_RaysGridIndex(benchmark::State& state) {
  const Scenario s = LoadScenario("loop");
  const StaticGeometryIndex index(StaticGeometryOf(MakeWorld(s)));
  const RaySet rays = LoopRays(s);
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(index.Cast(rays.origins[i], rays.dirs[i], 30.0));
    i = (i + 1) & 4095;
  }
  state.counters["rays_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

void BM_RaysBox2D(benchmark::State& state) {
  const Scenario s = LoadScenario("loop");
  const World world = MakeWorld(s);
  PhysicsWorld physics(s, world);
  const RaySet rays = LoopRays(s);
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(physics.RayCastBox2D(rays.origins[i], rays.dirs[i], 30.0));
    i = (i + 1) & 4095;
  }
  state.counters["rays_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

BENCHMARK(BM_RaysGridIndex);
BENCHMARK(BM_RaysBox2D);

const int kRegistered = [] {
  for (const std::string name : {"loop", "tunnel", "landmarks", "maze", "dynamic", "symmetric"})
    benchmark::RegisterBenchmark(("BM_Simulate/" + name).c_str(), BM_Simulate, name)
        ->Unit(benchmark::kMillisecond)
        ->MinTime(2.0);
  return 0;
}();

}  // namespace
}  // namespace slambox

BENCHMARK_MAIN();
