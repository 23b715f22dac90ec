#pragma once
// Test support: a synthetic sweep folder (sweep.json, results.csv, summary.md) in the
// layout `slambox sweep` writes: 2 scenarios x 2 modules x 6 seeds x a 3 x 2 grid.
#include <cmath>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>

#include "core/atomic_file.hpp"
#include <nlohmann/json.hpp>

namespace slambox::testing {

inline void WriteSyntheticSweep(const std::string& dir, std::uint64_t seed = 5) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n01(0.0, 1.0);
  const std::vector<std::string> scenarios{"loop", "tunnel"}, algos{"icp-poseslam", "odometry"};
  const std::vector<double> sigmas{0.01, 0.03, 0.05}, alphas{1.0, 2.0};
  nlohmann::json spec{{"scenarios", scenarios}, {"algorithms", algos}, {"seeds", {0, 1, 2, 3, 4, 5}},
                      {"grid", {{"sensors.lidar.sigma_range_m", sigmas}, {"sensors.odometry.alpha_scale", alphas}}},
                      {"interval", "auto"},
                      {"modules", {{"icp-poseslam", {{"baseline", false}}}, {"odometry", {{"baseline", true}}}}}};
  std::ostringstream csv;
  csv << "run_id,scenario,seed,algorithm,status,sensors.lidar.sigma_range_m,sensors.odometry.alpha_scale,ate_rmse_m,rpe_trans_rmse_m,anees\n";
  int run = 0;
  for (const auto& sc : scenarios)
    for (double s : sigmas)
      for (double a : alphas)
        for (int sd = 0; sd < 6; ++sd, ++run)
          for (const auto& al : algos) {
            const double base = al == "odometry" ? 1.5 * a : 0.05 + 2.0 * s;
            const double ate = base * (sc == "tunnel" ? 1.4 : 1.0) * std::exp(0.2 * n01(rng));
            csv << run << "," << sc << "," << sd << "," << al << ",ok," << s << "," << a << "," << ate << ","
                << 0.1 * ate << "," << (al == "odometry" ? "" : "3.1") << "\n";
          }
  std::filesystem::create_directories(dir);
  WriteFileAtomic(dir + "/sweep.json", spec.dump(2));
  WriteFileAtomic(dir + "/results.csv", csv.str());
  WriteFileAtomic(dir + "/summary.md", "# Sweep summary\n\n| scenario | algorithm | ate_rmse_m mean |\n|---|---|---|\n| loop | odometry | 2.2 |\n");
}

}  // namespace slambox::testing
