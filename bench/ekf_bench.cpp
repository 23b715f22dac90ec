// ekf-slam speed with 500 landmarks at 10 Hz landmark scans (odometry at 50 Hz).
// A robot drives a 100 m x 100 m square twice; 500 landmarks lie within 8 m of its path
// (range 10 m: about 25 in view per scan). Lap 1 builds the map (untimed), lap 2 is timed
// with every landmark in the state (3 + 2 * 500 = 1003 dimensions).
// Reports realtime_factor = simulated seconds of lap 2 / wall seconds to process them, and
// realtime_factor_cpu with this thread's CPU time instead (robust to a loaded machine).
#include <benchmark/benchmark.h>

#include <chrono>
#include <ctime>

#include "slam/ekf_slam.hpp"
#include "tests/support/synthetic_stream.hpp"

namespace slambox {
namespace {

struct BenchStream {
  Stream stream;
  size_t lap2_begin = 0;  ///< first event of the second lap
  double lap2_duration_s = 0.0;
};

const BenchStream& MakeBenchStream() {
  static const BenchStream bench = [] {
    testing::SyntheticOptions o;
    o.path = {{0, 0}, {100, 0}, {100, 100}, {0, 100}};
    o.laps = 2;
    o.seed = 42;
    o.sensors.odometry = OdometryConfig{};
    LandmarkSensorConfig lm;
    lm.range_max_m = 10.0;
    lm.known_ids = true;
    o.sensors.landmarks = lm;
    World world;
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> along(0.0, 400.0), across(-8.0, 8.0);
    for (int id = 0; id < 500; ++id) {  // uniformly along the path, within 8 m of it
      const double s = along(rng), d = across(rng);
      const int side = static_cast<int>(s / 100.0);
      const double u = s - 100.0 * side;
      const Eigen::Vector2d p = side == 0 ? Eigen::Vector2d(u, d)
                                : side == 1 ? Eigen::Vector2d(100 + d, u)
                                : side == 2 ? Eigen::Vector2d(100 - u, 100 + d)
                                            : Eigen::Vector2d(d, 100 - u);
      world.landmarks.push_back({id, p, 0.1});
    }
    BenchStream b;
    b.stream = testing::MakeSyntheticStream(o, world);
    const double half = b.stream.header.duration_s / 2;
    while (EventTime(b.stream.events[b.lap2_begin]) < half) ++b.lap2_begin;
    b.lap2_duration_s = b.stream.header.duration_s - half;
    return b;
  }();
  return bench;
}

double ObservationsPerScan(const Stream& stream) {
  double observations = 0.0, scans = 0.0;
  for (const auto& e : stream.events)
    if (const auto* l = std::get_if<LandmarkEvent>(&e)) observations += l->observations.size(), scans += 1.0;
  return observations / scans;
}

void Feed(EkfSlam& ekf, const SensorEvent& event) {
  if (const auto* o = std::get_if<OdometryEvent>(&event)) ekf.OnOdometry(*o);
  else if (const auto* l = std::get_if<LandmarkEvent>(&event)) ekf.OnLandmarks(*l);
}

double ThreadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

void BM_EkfSlam500Landmarks(benchmark::State& state) {
  const BenchStream& b = MakeBenchStream();
  int landmarks = 0;
  double total_wall_s = 0.0, total_cpu_s = 0.0, total_sim_s = 0.0;
  for (auto _ : state) {
    EkfSlam ekf({});
    ekf.Start(b.stream.header);
    for (size_t i = 0; i < b.lap2_begin; ++i) Feed(ekf, b.stream.events[i]);
    const auto t0 = std::chrono::steady_clock::now();
    const double cpu0 = ThreadCpuSeconds();
    for (size_t i = b.lap2_begin; i < b.stream.events.size(); ++i) Feed(ekf, b.stream.events[i]);
    const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    total_cpu_s += ThreadCpuSeconds() - cpu0;
    state.SetIterationTime(wall_s);
    total_wall_s += wall_s;
    total_sim_s += b.lap2_duration_s;
    landmarks = ekf.state().NumLandmarks();
  }
  state.counters["landmarks"] = landmarks;
  state.counters["sim_s"] = b.lap2_duration_s;
  state.counters["realtime_factor"] = total_sim_s / total_wall_s;  // lap 2 only
  state.counters["realtime_factor_cpu"] = total_sim_s / total_cpu_s;
  state.counters["obs_per_scan"] = ObservationsPerScan(b.stream);
}
BENCHMARK(BM_EkfSlam500Landmarks)->UseManualTime()->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace slambox

BENCHMARK_MAIN();
