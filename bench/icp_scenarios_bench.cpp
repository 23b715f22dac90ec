// Accuracy and speed of odometry / icp-odometry / icp-poseslam on the built-in scenarios
// loop, tunnel and symmetric over seeds 0..N-1 (issue 5 targets). Prints one line per
// scenario, seed and algorithm: ATE RMSE (no alignment, matched timestamps), loop closures
// proposed/accepted (accepted false = between poses whose true positions are > 1 m apart
// after applying the measured relative pose), and the real-time factor of the module
// (stream duration over wall time, and over process CPU time).
//   ./build/bench/icp_scenarios_bench [seeds=10] [scenario ...] [FIELD=VALUE ...]
// FIELD=VALUE pairs override both ICP modules' parameters (e.g. robust_kernel=huber);
// icp-poseslam.FIELD=VALUE only icp-poseslam's (e.g. icp-poseslam.loop_region=true).
#include <chrono>
#include <ctime>
#include <cstdio>
#include <map>
#include <string>

#include "sim/scenario.hpp"
#include "sim/simulate.hpp"
#include "slam/dead_reckoning.hpp"
#include "slam/icp_odometry.hpp"
#include "slam/icp_poseslam.hpp"

using namespace slambox;

namespace {
double AteRmse(const Estimate& e, const Stream& s) {
  std::map<double, SE2> gt;
  for (const auto& g : s.groundtruth) gt[g.t_s] = g.pose;
  double sum = 0;
  int n = 0;
  for (const auto& p : e.trajectory)
    if (auto it = gt.find(p.t_s); it != gt.end()) sum += (p.pose.translation() - it->second.translation()).squaredNorm(), ++n;
  return n ? std::sqrt(sum / n) : NAN;
}

/// Accepted closures whose measured relative pose is > 1 m off the true one.
int FalseAccepted(const Estimate& e, const Stream& s) {
  std::map<double, SE2> gt;
  for (const auto& g : s.groundtruth) gt[g.t_s] = g.pose;
  int bad = 0;
  for (const auto& lc : e.loop_closures) {
    if (!lc.accepted) continue;
    const SE2 truth = Between(gt.at(lc.t_from_s), gt.at(lc.t_to_s));
    if ((truth.translation() - lc.T_from_to.translation()).norm() > 1.0) ++bad;
  }
  return bad;
}
}  // namespace

int main(int argc, char** argv) {
  const int seeds = argc > 1 ? std::atoi(argv[1]) : 10;
  std::vector<std::string> scenarios;
  ParamOverrides overrides, poseslam_overrides;
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    const auto eq = arg.find('=');
    if (eq == std::string::npos) scenarios.push_back(arg);
    else if (arg.rfind("icp-poseslam.", 0) == 0) poseslam_overrides[arg.substr(13, eq - 13)] = arg.substr(eq + 1);
    else overrides[arg.substr(0, eq)] = arg.substr(eq + 1);
  }
  if (scenarios.empty()) scenarios = {"loop", "tunnel", "symmetric"};
  const std::vector<ModuleInfo> modules = {DeadReckoningModule(), IcpOdometryModule(), IcpPoseSlamModule()};
  std::printf("%-10s %4s %-13s %9s %6s %6s %6s %8s %8s\n", "scenario", "seed", "algorithm", "ate_m", "loops", "acc",
              "false", "rt_wall", "rt_cpu");
  for (const auto& name : scenarios) {
    const Scenario scenario = LoadScenario(name);
    std::map<std::string, std::vector<double>> ates;
    for (int seed = 0; seed < seeds; ++seed) {
      const Stream s = Simulate(scenario, static_cast<std::uint64_t>(seed));
      for (const auto& m : modules) {
        ParamOverrides o = m.name == "odometry" ? ParamOverrides{} : overrides;
        if (m.name == "icp-poseslam") o.insert(poseslam_overrides.begin(), poseslam_overrides.end());
        auto module = m.create(o);
        const auto t0 = std::chrono::steady_clock::now();
        const std::clock_t c0 = std::clock();
        const Estimate e = Replay(*module, s);
        const double cpu = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
        const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        int acc = 0;
        for (const auto& lc : e.loop_closures) acc += lc.accepted;
        const double ate = AteRmse(e, s);
        ates[m.name].push_back(ate);
        std::printf("%-10s %4d %-13s %9.4f %6zu %6d %6d %8.1f %8.1f\n", name.c_str(), seed, m.name.c_str(), ate,
                    e.loop_closures.size(), acc, FalseAccepted(e, s), s.header.duration_s / wall,
                    s.header.duration_s / cpu);
        std::fflush(stdout);
      }
    }
    for (const auto& [algo, v] : ates) {
      double mean = 0, worst = 0;
      for (double a : v) mean += a / v.size(), worst = std::max(worst, a);
      std::printf("# %-10s %-13s mean ATE %.4f m, worst %.4f m over %zu seeds\n", name.c_str(), algo.c_str(), mean,
                  worst, v.size());
    }
  }
}
