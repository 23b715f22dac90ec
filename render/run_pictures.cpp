#include "render/run_pictures.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "render/figures_run_parts.hpp"

namespace slambox::render {

namespace fs = std::filesystem;

namespace {
// 800 px at 2x2 samples: about a quarter of a run figure's pixels, enough for a report
// column (1400 px screens show two side by side).
constexpr FigureOutput kPicture{.width_px = 800, .supersample = 2, .svg = false};
}  // namespace

std::string SafeFileName(const std::string& name) {
  std::string s = name;
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  return s;
}

std::vector<std::string> RenderRunPictures(const RunFolder& run, const std::string& run_dir) {
  fs::create_directories(fs::path(run_dir) / kPicturesDir);
  std::vector<std::string> written;
  auto emit = [&](const std::string& name, auto&& draw) {
    const std::string rel = std::string(kPicturesDir) + "/" + name;
    if (draw((fs::path(run_dir) / rel).string())) written.push_back(rel);
  };
  // A converted log has no world and no ground truth: its paths alone say little, its maps show it.
  if (run.has_world || !run.groundtruth.empty())
    emit("trajectories", [&](const std::string& s) { return DrawTrajectoriesFigure(run, s, nullptr, -1.0, kPicture); });
  for (size_t i = 0; i < run.algorithms.size(); ++i)
    emit("map_" + SafeFileName(run.algorithms[i].name),
         [&](const std::string& s) { return DrawMapFigure(run, i, s, kPicture); });
  return written;
}

Representative RepresentativeRun(const std::vector<const ResultRow*>& rows) {
  Representative out;
  std::vector<std::pair<std::uint64_t, std::string>> seeds;  // (seed, run_id), by seed
  std::map<std::string, std::vector<std::pair<double, std::uint64_t>>> by_module;  // module -> (ATE, seed)
  for (const ResultRow* r : rows) {
    if (std::none_of(seeds.begin(), seeds.end(), [&](const auto& s) { return s.first == r->seed; }))
      seeds.push_back({r->seed, r->run_id});
    const auto it = r->metrics.find("ate_rmse_m");
    const double ate = r->status == "ok" && it != r->metrics.end() && std::isfinite(it->second) ? it->second : INFINITY;
    by_module[r->algorithm].push_back({ate, r->seed});
  }
  if (seeds.empty()) return out;
  std::sort(seeds.begin(), seeds.end());
  std::map<std::uint64_t, double> rank_sum;
  for (auto& [module, v] : by_module) {
    std::sort(v.begin(), v.end());  // by ATE, ties by seed
    for (size_t k = 0; k < v.size(); ++k) rank_sum[v[k].second] += static_cast<double>(k);
  }
  std::vector<std::pair<double, std::uint64_t>> order;  // (rank sum, seed)
  for (const auto& [seed, id] : seeds) order.push_back({rank_sum[seed], seed});
  std::sort(order.begin(), order.end());
  const std::uint64_t chosen = order[(order.size() - 1) / 2].second;
  for (const auto& [seed, id] : seeds)
    if (seed == chosen) out.run_id = id;
  out.seed = chosen;
  out.seeds = static_cast<int>(seeds.size());
  return out;
}

}  // namespace slambox::render
