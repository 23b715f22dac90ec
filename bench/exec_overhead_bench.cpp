// Overhead of the exec protocol per event (issue 15 target: <= 5 us): the same
// odometry-only stream replayed to the built-in `odometry` and to an exec child that
// echoes dead reckoning (bench/exec_echo_child.cpp). Reports wall time per event of both,
// their difference, and slambox's own CPU time per event in the exec run (serializing,
// pipe writes, reading and validating the answers).
//   ./build/bench/exec_overhead_bench [EVENTS]
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "app/exec_module.hpp"
#include "slam/dead_reckoning.hpp"

using namespace slambox;

namespace {

double CpuSeconds(int who) {
  rusage u{};
  getrusage(who, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

struct Timing {
  double wall_s, self_cpu_s, child_cpu_s;
  std::size_t poses;
};

Timing Time(const ModuleInfo& info, const Stream& stream) {
  const double self0 = CpuSeconds(RUSAGE_SELF), child0 = CpuSeconds(RUSAGE_CHILDREN);
  const auto t0 = std::chrono::steady_clock::now();
  const auto module = info.create({});
  const Estimate e = Replay(*module, stream);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return {wall, CpuSeconds(RUSAGE_SELF) - self0, CpuSeconds(RUSAGE_CHILDREN) - child0, e.trajectory.size()};
}

}  // namespace

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 500000;
  Stream stream;
  stream.header.sensors.odometry = OdometryConfig{};
  std::mt19937_64 rng(1);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (int i = 1; i <= n; ++i)
    stream.events.push_back(OdometryEvent{i * 0.02, SE2(0.02 + 0.002 * noise(rng), 1e-4 * noise(rng), 0.01 * noise(rng))});
  ExecDeclaration echo;
  echo.name = "exec:echo";
  echo.file = "(bench)";
  echo.command = {EXEC_ECHO_CHILD};
  const ModuleInfo exec = ExecModuleInfo(echo), builtin = DeadReckoningModule();
  std::printf("%d odometry events; median of 5 runs each\n", n);
  std::vector<Timing> b, x;
  for (int rep = 0; rep < 5; ++rep) b.push_back(Time(builtin, stream)), x.push_back(Time(exec, stream));
  const auto median = [](std::vector<Timing> v, auto key) {
    std::sort(v.begin(), v.end(), [&](const Timing& l, const Timing& r) { return key(l) < key(r); });
    return key(v[v.size() / 2]);
  };
  const auto wall = [](const Timing& t) { return t.wall_s; };
  const auto self = [](const Timing& t) { return t.self_cpu_s; };
  const auto child = [](const Timing& t) { return t.child_cpu_s; };
  const double us = 1e6 / n;
  std::printf("built-in odometry: wall %.3f us/event\n", median(b, wall) * us);
  std::printf("exec echo child:   wall %.3f us/event, slambox CPU %.3f us/event, child CPU %.3f us/event (%zu poses)\n",
              median(x, wall) * us, median(x, self) * us, median(x, child) * us, x[0].poses);
  std::printf("protocol overhead (exec wall - built-in wall): %.3f us/event\n", (median(x, wall) - median(b, wall)) * us);
  return x[0].poses == static_cast<std::size_t>(n) + 1 ? 0 : 1;
}
