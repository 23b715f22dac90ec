// ICP pair benchmark (issue 5): two 360-beam scans of a room, range noise sigma 1 cm, true
// motion 0.16 m / 3 deg, registration started at identity. Each iteration registers the
// next of 64 pre-generated pairs (different noise); counters report the median
// translation / rotation error over the pairs. Time includes building the target
// (normals, beam index or kd-tree) from the reference scan's points.
//   ./build/bench/icp_bench --benchmark_filter=Icp
#include <benchmark/benchmark.h>

#include <algorithm>
#include <random>

#include "slam/icp.hpp"
#include "tests/support/synthetic_scan.hpp"

namespace slambox {
namespace {

struct BenchPair {
  LaserScanEvent reference;
  ScanPoints reference_points, source_points;
};

const SE2 kTrueMotion(0.16 * std::cos(0.3), 0.16 * std::sin(0.3), 3.0 * M_PI / 180);

const std::vector<BenchPair>& Pairs() {
  static const std::vector<BenchPair> pairs = [] {
    std::vector<BenchPair> out;
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> ux(-2.5, 2.5), uy(-1.5, 1.5), ua(-M_PI, M_PI);
    for (int i = 0; i < 64; ++i) {
      const SE2 A(ux(rng), uy(rng), ua(rng));
      BenchPair p;
      p.reference = testing::RayCastScan(testing::RoomWalls(), A, 360, 0.01, rng);
      const LaserScanEvent src = testing::RayCastScan(testing::RoomWalls(), A * kTrueMotion, 360, 0.01, rng);
      p.reference_points = ScanToPoints(p.reference);
      p.source_points = ScanToPoints(src);
      out.push_back(std::move(p));
    }
    return out;
  }();
  return pairs;
}

double Median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

void RunIcpPair(benchmark::State& state, IcpMetric metric, IcpCorrespondence corr) {
  const auto& pairs = Pairs();
  IcpConfig config;
  config.metric = metric;
  config.correspondence = corr;
  if (metric == IcpMetric::kPointToPoint) config.max_iterations = 100;
  IcpTargetConfig target_config;
  target_config.build_kd_tree = corr == IcpCorrespondence::kKdTree;
  std::vector<double> err_t(pairs.size()), err_r(pairs.size()), iters(pairs.size());
  size_t k = 0;
  for (auto _ : state) {
    const BenchPair& p = pairs[k % pairs.size()];
    const IcpTarget target = MakeScanTarget(p.reference_points, p.reference, target_config);
    const IcpResult r = RegisterIcp(p.source_points.points, target, SE2(), config);
    benchmark::DoNotOptimize(r.T_target_source);
    if (k < pairs.size()) {
      err_t[k] = (r.T_target_source.translation() - kTrueMotion.translation()).norm();
      err_r[k] = std::abs(NormalizeAngle(r.T_target_source.theta - kTrueMotion.theta));
      iters[k] = r.iterations;
    }
    ++k;
  }
  const size_t n = std::min(k, pairs.size());
  err_t.resize(n), err_r.resize(n), iters.resize(n);
  state.counters["median_trans_err_mm"] = Median(err_t) * 1e3;
  state.counters["median_rot_err_deg"] = Median(err_r) * 180 / M_PI;
  state.counters["median_iterations"] = Median(iters);
}

void BM_IcpPointToLineProjection(benchmark::State& s) {
  RunIcpPair(s, IcpMetric::kPointToLine, IcpCorrespondence::kProjection);
}
void BM_IcpPointToLineKdTree(benchmark::State& s) { RunIcpPair(s, IcpMetric::kPointToLine, IcpCorrespondence::kKdTree); }
void BM_IcpPointToPointProjection(benchmark::State& s) {
  RunIcpPair(s, IcpMetric::kPointToPoint, IcpCorrespondence::kProjection);
}
void BM_IcpPointToPointKdTree(benchmark::State& s) {
  RunIcpPair(s, IcpMetric::kPointToPoint, IcpCorrespondence::kKdTree);
}
BENCHMARK(BM_IcpPointToLineProjection)->Unit(benchmark::kMicrosecond)->Repetitions(5)->ReportAggregatesOnly();
BENCHMARK(BM_IcpPointToLineKdTree)->Unit(benchmark::kMicrosecond)->Repetitions(5)->ReportAggregatesOnly();
BENCHMARK(BM_IcpPointToPointProjection)->Unit(benchmark::kMicrosecond)->Repetitions(5)->ReportAggregatesOnly();
BENCHMARK(BM_IcpPointToPointKdTree)->Unit(benchmark::kMicrosecond)->Repetitions(5)->ReportAggregatesOnly();

}  // namespace
}  // namespace slambox

BENCHMARK_MAIN();
