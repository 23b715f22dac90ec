#include "render/run_folder.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "core/json_io.hpp"
#include "core/tum.hpp"

namespace slambox::render {

namespace fs = std::filesystem;

nlohmann::json ReadJsonFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "cannot open the file", "check the path; `slambox run` writes it");
  std::stringstream buf;
  buf << in.rdbuf();
  const std::string text = buf.str();
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    const size_t upto = std::min(text.size(), static_cast<size_t>(e.byte));
    const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + upto, '\n'));
    throw InputError(path, line, std::string("malformed JSON: ") + e.what(), "re-run the command that wrote it");
  }
}

std::vector<double> NumbersOf(const nlohmann::json& j, const std::string& key) {
  std::vector<double> out;
  if (!j.is_object() || !j.contains(key) || !j.at(key).is_array()) return out;
  for (const auto& v : j.at(key)) out.push_back(v.is_number() ? v.get<double>() : std::nan(""));
  return out;
}

namespace {
ErrorSeries SeriesFromJson(const nlohmann::json& j) {
  ErrorSeries s;
  s.t_s = NumbersOf(j, "t_s");
  s.distance_m = NumbersOf(j, "distance_m");
  s.ate_m = NumbersOf(j, "ate_m");
  s.heading_error_deg = NumbersOf(j, "heading_error_deg");
  s.nees = NumbersOf(j, "nees");
  const std::vector<double> band = NumbersOf(j, "nees_band_95");
  if (band.size() == 2) {
    s.nees_band_lo = band[0];
    s.nees_band_hi = band[1];
  }
  if (j.contains("rpe") && j.at("rpe").is_object()) {
    s.rpe_distance_m = NumbersOf(j.at("rpe"), "distance_m");
    s.rpe_trans_m = NumbersOf(j.at("rpe"), "trans_m");
    s.rpe_rot_deg = NumbersOf(j.at("rpe"), "rot_deg");
  }
  return s;
}

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
    a.metrics = entry;
    a.status = entry.is_object() ? entry.value("status", std::string("ok")) : "ok";
    const fs::path tum = fs::path(dir) / (name + ".tum");
    if (fs::exists(tum)) a.trajectory = ReadTum(tum.string());
    const fs::path est = fs::path(dir) / "estimates" / (name + ".json");
    if (fs::exists(est)) a.estimate = Parsed(est.string(), [](const nlohmann::json& j) { return EstimateFromJson(j); });
    const fs::path ser = fs::path(dir) / "series" / (name + ".json");
    if (fs::exists(ser)) a.series = Parsed(ser.string(), [](const nlohmann::json& j) { return SeriesFromJson(j); });
    run.algorithms.push_back(std::move(a));
  }
  return run;
}

}  // namespace slambox::render
