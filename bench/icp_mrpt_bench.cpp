// MRPT's CICP against slambox's ICP on the same scan pairs: two 360-beam scans of a room
// (σ_range 1 cm), true motion 0.16 m forward and 3° left, initial guess = identity.
// Each registration starts from the two raw scans, so both sides pay for their own
// preprocessing: MRPT builds two point maps and its kd-tree; slambox converts both scans to
// points and builds its target (normals, beam index; projection needs no kd-tree, so the
// target builds none). Beam cos/sin are cached per sensor geometry by both libraries
// (slambox per thread, MRPT per points map, i.e. recomputed here for every new map).
// Counters: median_time_ms per registration, median_trans_err_mm, median_rot_err_mdeg.
//   ./build/bench/icp_mrpt_bench
#include <benchmark/benchmark.h>

#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/poses/CPosePDF.h>
#include <mrpt/slam/CICP.h>

#include <algorithm>
#include <chrono>
#include <random>

#include "sim/ray_caster.hpp"
#include "slam/mrpt/mrpt_convert.hpp"
#if __has_include("slam/icp.hpp")
#include "slam/icp.hpp"
#include "slam/icp_target.hpp"
#include "slam/scan_points.hpp"
#define SLAMBOX_HAS_ICP 1
#endif

namespace slambox {
namespace {

constexpr int kPairs = 32;
const SE2 kMotion(0.16, 0.0, 3.0 * M_PI / 180.0);

std::vector<Segment> Room() {
  std::vector<Segment> w;
  auto box = [&w](Eigen::Vector2d lo, Eigen::Vector2d hi) {
    const Eigen::Vector2d c[4] = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
    for (int i = 0; i < 4; ++i) w.push_back({c[i], c[(i + 1) % 4]});
  };
  box({0.0, 0.0}, {8.0, 6.0});   // walls
  box({1.0, 4.2}, {2.2, 5.0});   // furniture, so the room is not symmetric
  box({5.5, 0.8}, {6.3, 1.6});
  return w;
}

LaserScanEvent Scan(const std::vector<Segment>& room, const SE2& pose, std::mt19937_64& rng) {
  LaserScanEvent s;
  s.angle_increment_rad = 2 * M_PI / 360;
  s.angle_min_rad = -M_PI;
  s.range_min_m = 0.1;
  s.range_max_m = 20.0;
  std::normal_distribution<double> noise(0.0, 0.01);
  for (int b = 0; b < 360; ++b) {
    const double a = pose.theta + s.angle_min_rad + b * s.angle_increment_rad;
    const Eigen::Vector2d dir(std::cos(a), std::sin(a));
    double r = kNoHit;
    for (const auto& seg : room) r = std::min(r, RaySegmentRange(pose.translation(), dir, s.range_max_m, seg.a, seg.b));
    const bool hit = r < s.range_max_m;
    s.ranges_m.push_back(hit ? r + noise(rng) : s.range_max_m);
    s.valid.push_back(hit ? 1 : 0);
  }
  return s;
}

struct ScanPair {
  LaserScanEvent reference, current;
};

const std::vector<ScanPair>& Pairs() {
  static const std::vector<ScanPair> pairs = [] {
    const auto room = Room();
    std::vector<ScanPair> out;
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> x(2.5, 4.5), y(2.0, 3.5), th(-M_PI, M_PI);
    for (int i = 0; i < kPairs; ++i) {
      const SE2 p0(x(rng), y(rng), th(rng));
      out.push_back({Scan(room, p0, rng), Scan(room, p0 * kMotion, rng)});
    }
    return out;
  }();
  return pairs;
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

/// Runs `register_pair(pair) -> SE2 estimate of T_reference_current` over the pairs.
template <class Register>
void RunRegistrations(benchmark::State& state, Register register_pair) {
  std::vector<double> times_ms, trans_err_mm, rot_err_mdeg;
  size_t i = 0;
  for (auto _ : state) {
    const ScanPair& pair = Pairs()[i++ % Pairs().size()];
    const auto t0 = std::chrono::steady_clock::now();
    const SE2 est = register_pair(pair);
    times_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    trans_err_mm.push_back(1e3 * (est.translation() - kMotion.translation()).norm());
    rot_err_mdeg.push_back(1e3 * std::abs(NormalizeAngle(est.theta - kMotion.theta)) * 180.0 / M_PI);
  }
  state.counters["median_time_ms"] = Median(times_ms);
  state.counters["median_trans_err_mm"] = Median(trans_err_mm);
  state.counters["median_rot_err_mdeg"] = Median(rot_err_mdeg);
}

void BM_MrptCicp(benchmark::State& state, mrpt::slam::TICPAlgorithm algorithm) {
  RunRegistrations(state, [algorithm](const ScanPair& pair) {
    mrpt::maps::CSimplePointsMap reference, current;
    for (auto* m : {&reference, &current}) {
      m->insertionOptions.minDistBetweenLaserPoints = 0.0f;
      m->insertionOptions.also_interpolate = false;
    }
    reference.insertObservation(mrpt_bridge::ToMrptScan(pair.reference, 0.01));
    current.insertObservation(mrpt_bridge::ToMrptScan(pair.current, 0.01));
    mrpt::slam::CICP icp;
    icp.options.ICP_algorithm = algorithm;
    icp.options.thresholdDist = 0.75;
    icp.options.ALFA = 0.5;
    icp.options.maxIterations = 80;
    mrpt::slam::CICP::TReturnInfo info;
    const auto pdf = icp.Align(&reference, &current, mrpt::poses::CPose2D(0, 0, 0), info);
    return mrpt_bridge::FromMrpt(pdf->getMeanVal());
  });
}
BENCHMARK_CAPTURE(BM_MrptCicp, icpClassic, mrpt::slam::icpClassic)->Unit(benchmark::kMillisecond)->Iterations(320);
BENCHMARK_CAPTURE(BM_MrptCicp, icpLevenbergMarquardt, mrpt::slam::icpLevenbergMarquardt)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(320);

#ifdef SLAMBOX_HAS_ICP
void BM_SlamboxIcp(benchmark::State& state, IcpMetric metric) {
  RunRegistrations(state, [metric](const ScanPair& pair) {
    const ScanPoints reference = ScanToPoints(pair.reference);
    const ScanPoints current = ScanToPoints(pair.current);
    const IcpTarget target = MakeScanTarget(reference, pair.reference);
    IcpConfig config;
    config.metric = metric;
    // Correspondences by projection into the reference scan's beams (constant time), the
    // variant icp_bench times; other fields at IcpConfig's defaults.
    config.correspondence = IcpCorrespondence::kProjection;
    return RegisterIcp(current.points, target, SE2(), config).T_target_source;
  });
}
BENCHMARK_CAPTURE(BM_SlamboxIcp, point_to_point, IcpMetric::kPointToPoint)->Unit(benchmark::kMillisecond)->Iterations(320);
BENCHMARK_CAPTURE(BM_SlamboxIcp, point_to_line, IcpMetric::kPointToLine)->Unit(benchmark::kMillisecond)->Iterations(320);
#endif

}  // namespace
}  // namespace slambox

BENCHMARK_MAIN();
