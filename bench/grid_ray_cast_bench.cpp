// LIDAR casting against a 2000 x 2000 occupancy grid (0.05 m cells, 100 m x 100 m): the
// loop scenario's walls rasterized into the grid, 4096 rays from poses along its path,
// 30 m range. Counters: rays_per_s, and scan_realtime_factor = scans of 360 beams per
// second / 10 Hz (the LIDAR of loop): the ray casting alone, not the whole simulation.
// The segment index on the same rays for reference, and the whole simulation of loop
// with its world given as that 2000 x 2000 grid (world.occupancy_map: its cells' boundary
// loops become the walls). Run: ./build/bench/grid_ray_cast_bench
#include <benchmark/benchmark.h>

#include <random>

#include "eval/grid_map.hpp"
#include "sim/grid_ray_cast.hpp"
#include "sim/ray_caster.hpp"
#include "sim/scenario.hpp"
#include "sim/simulate.hpp"

namespace slambox {
namespace {

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

OccupancyGrid LoopGrid(const World& world) {
  OccupancyGrid g;
  g.resolution_m = 0.05;
  g.width = g.height = 2000;
  g.origin_m = {-27.0, -36.0};  // the 46 m x 28 m building in the middle of 100 m x 100 m
  const auto mask = RasterizeWorld(world, g);
  g.cells.resize(mask.size());
  for (size_t i = 0; i < mask.size(); ++i) g.cells[i] = mask[i] ? 100 : 0;
  return g;
}

void Counters(benchmark::State& state) {
  state.counters["rays_per_s"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["scan_realtime_factor"] =
      benchmark::Counter(static_cast<double>(state.iterations()) / 360.0 / 10.0, benchmark::Counter::kIsRate);
}

void BM_GridRays2000(benchmark::State& state) {
  const Scenario s = LoadScenario("loop");
  const OccupancyGrid grid = LoopGrid(MakeWorld(s));
  const GridRayCaster caster(grid);
  const RaySet rays = LoopRays(s);
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(caster.Cast(rays.origins[i], rays.dirs[i], 30.0));
    i = (i + 1) & 4095;
  }
  Counters(state);
}

void BM_SegmentIndexRays(benchmark::State& state) {
  const Scenario s = LoadScenario("loop");
  const StaticGeometryIndex index(StaticGeometryOf(MakeWorld(s)));
  const RaySet rays = LoopRays(s);
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(index.Cast(rays.origins[i], rays.dirs[i], 30.0));
    i = (i + 1) & 4095;
  }
  Counters(state);
}

void BM_SimulateLoopFromGrid2000(benchmark::State& state) {
  Scenario s = LoadScenario("loop");
  s.occupancy_grid = LoopGrid(MakeWorld(s));
  s.walls.clear();
  double simulated_s = 0.0;
  std::size_t walls = 0;
  for (auto _ : state) {
    const Stream stream = Simulate(s, 0);
    simulated_s += stream.header.duration_s;
    walls = stream.header.world.wall_segments.size();
  }
  state.counters["realtime_factor"] = benchmark::Counter(simulated_s, benchmark::Counter::kIsRate);
  state.counters["wall_segments"] = static_cast<double>(walls);
}

BENCHMARK(BM_GridRays2000);
BENCHMARK(BM_SimulateLoopFromGrid2000)->Unit(benchmark::kMillisecond)->MinTime(2.0);
BENCHMARK(BM_SegmentIndexRays);

}  // namespace
}  // namespace slambox

BENCHMARK_MAIN();
