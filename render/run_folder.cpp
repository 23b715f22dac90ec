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

bool BaselineFlag(const nlohmann::json& doc, const std::string& name, const std::string& path) {
  if (!doc.contains("modules")) return false;  // written before the flag existed: no module is one
  const nlohmann::json& modules = doc.at("modules");
  if (!modules.is_object() || !modules.contains(name)) return false;
  const nlohmann::json& m = modules.at(name);
  if (!m.is_object() || !m.contains("baseline")) return false;
  if (!m.at("baseline").is_boolean())
    throw InputError(path, 0, "modules." + name + ".baseline is not true or false", "re-run to rewrite the file");
  return m.at("baseline").get<bool>();
}

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
    run.has_world = WorldHasGeometry(run.world);
  }
  const fs::path gt_path = fs::path(dir) / "groundtruth.tum";
  if (fs::exists(gt_path)) run.groundtruth = ReadTum(gt_path.string());
  run.converted_log = run.metrics.value("converted_log", run.groundtruth.empty());
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
    a.baseline = BaselineFlag(run.metrics, name, metrics_path);
    run.algorithms.push_back(std::move(a));
  }
  return run;
}

}  // namespace slambox::render
