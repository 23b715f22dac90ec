#include "render/run_folder.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "core/json_io.hpp"
#include "core/tum.hpp"

namespace slambox::render {

namespace fs = std::filesystem;

namespace {
template <typename F>
auto Parsed(const std::string& path, F&& parse) {
  try {
    return parse(ReadJsonFile(path));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path, 0, std::string("unexpected content: ") + e.what(), "re-run `slambox run`");
  }
}
}  // namespace

RunFolder ReadRunFolder(const std::string& dir) {
  RunFolder run;
  run.dir = dir;
  const std::string metrics_path = (fs::path(dir) / "metrics.json").string();
  if (!fs::exists(metrics_path))
    throw InputError(metrics_path, 0, "not a run folder (no metrics.json)", "pass a folder written by `slambox run -o DIR`");
  run.metrics = ReadJsonFile(metrics_path);
  run.scenario = run.metrics.value("scenario", std::string());
  run.seed = run.metrics.value("seed", 0L);
  const fs::path world_path = fs::path(dir) / "world.json";
  if (fs::exists(world_path)) {
    run.world = Parsed(world_path.string(), [](const nlohmann::json& j) { return WorldFromJson(j.at("world")); });
    // A converted real log has an empty world: nothing true to draw.
    const World& w = run.world;
    run.has_world = !w.wall_segments.empty() || !w.wall_circles.empty() || !w.landmarks.empty() || !w.movers.empty();
  }
  const fs::path gt_path = fs::path(dir) / "groundtruth.tum";
  if (fs::exists(gt_path)) run.groundtruth = ReadTum(gt_path.string());
  if (!run.metrics.contains("algorithms") || !run.metrics.at("algorithms").is_object())
    throw InputError(metrics_path, 0, "no \"algorithms\" object", "re-run `slambox run`");
  for (const auto& [name, entry] : run.metrics.at("algorithms").items()) {
    AlgorithmResult a;
    a.name = name;
    a.metrics = MetricsFromJson(entry, metrics_path);
    const fs::path tum = fs::path(dir) / (name + ".tum");
    if (fs::exists(tum)) a.trajectory = ReadTum(tum.string());
    const fs::path est = fs::path(dir) / "estimates" / (name + ".json");
    if (fs::exists(est)) a.estimate = Parsed(est.string(), [](const nlohmann::json& j) { return EstimateFromJson(j); });
    const fs::path ser = fs::path(dir) / "series" / (name + ".json");
    if (fs::exists(ser))
      a.series = Parsed(ser.string(), [&](const nlohmann::json& j) { return ErrorSeriesFromJson(j, ser.string()); });
    run.algorithms.push_back(std::move(a));
  }
  return run;
}

}  // namespace slambox::render
