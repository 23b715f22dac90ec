#include "render/sweep_folder.hpp"

#include <algorithm>
#include <filesystem>

#include "core/error.hpp"
#include "core/json_io.hpp"
#include "render/run_folder.hpp"

namespace slambox::render {

SweepFolder ReadSweepFolder(const std::string& dir) {
  namespace fs = std::filesystem;
  SweepFolder sw;
  sw.dir = dir;
  const nlohmann::json spec = ReadJsonFile((fs::path(dir) / "sweep.json").string());
  auto strings = [&](const char* key) {
    std::vector<std::string> out;
    if (spec.contains(key) && spec.at(key).is_array())
      for (const auto& v : spec.at(key)) out.push_back(v.is_string() ? v.get<std::string>() : v.dump());
    return out;
  };
  sw.scenarios = strings("scenarios");
  sw.algorithms = strings("algorithms");
  sw.results = ReadResultsCsv((fs::path(dir) / "results.csv").string());
  const auto& rows = sw.results.rows;
  // Only algorithms that have rows (sweep.json may say `all`), in sweep.json's order, then
  // the rows' own order; the same fallback for scenarios.
  std::erase_if(sw.algorithms, [&](const std::string& a) {
    return std::none_of(rows.begin(), rows.end(), [&](const auto& r) { return r.algorithm == a; });
  });
  for (const auto& r : rows) {
    if (std::find(sw.scenarios.begin(), sw.scenarios.end(), r.scenario) == sw.scenarios.end()) sw.scenarios.push_back(r.scenario);
    if (std::find(sw.algorithms.begin(), sw.algorithms.end(), r.algorithm) == sw.algorithms.end()) sw.algorithms.push_back(r.algorithm);
  }
  const std::string path = (fs::path(dir) / "sweep.json").string();
  for (const auto& a : sw.algorithms) sw.baseline.push_back(BaselineFlag(spec, a, path));
  if (spec.contains("interval")) {
    const auto m = IntervalMethodFromName(spec.at("interval").is_string() ? spec.at("interval").get<std::string>() : "");
    if (m) sw.interval = *m;
    else throw InputError(path, 0, "interval must be auto, t or bootstrap", "re-run the sweep to rewrite sweep.json");
  }
  return sw;
}

}  // namespace slambox::render
