#include "render/sweep_folder.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "eval/statistics.hpp"
#include "render/run_folder.hpp"

namespace slambox::render {

namespace {
std::vector<std::string> SplitCsv(const std::string& line) {
  std::vector<std::string> cells(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '"') {
      if (quoted && i + 1 < line.size() && line[i + 1] == '"') cells.back() += '"', ++i;
      else quoted = !quoted;
    } else if (c == ',' && !quoted) {
      cells.emplace_back();
    } else if (c != '\r') {
      cells.back() += c;
    }
  }
  return cells;
}

double Quantile(const std::vector<double>& sorted, double p) {
  const double h = (sorted.size() - 1) * p;
  const size_t lo = static_cast<size_t>(std::floor(h));
  const size_t hi = std::min(sorted.size() - 1, lo + 1);
  return sorted[lo] + (h - lo) * (sorted[hi] - sorted[lo]);
}

}  // namespace

GroupStats Describe(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  GroupStats s;
  s.n = static_cast<int>(v.size());
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  s.q1 = Quantile(v, 0.25);
  s.median = Quantile(v, 0.5);
  s.q3 = Quantile(v, 0.75);
  const double iqr = s.q3 - s.q1, lo_fence = s.q1 - 1.5 * iqr, hi_fence = s.q3 + 1.5 * iqr;
  s.whisker_lo = s.q1;
  s.whisker_hi = s.q3;
  for (double x : v) {
    if (x < lo_fence || x > hi_fence) s.outliers.push_back(x);
    else {
      s.whisker_lo = std::min(s.whisker_lo, x);
      s.whisker_hi = std::max(s.whisker_hi, x);
    }
  }
  double sum = 0.0;
  for (double x : v) sum += x;
  s.mean = sum / s.n;
  if (s.n >= 2) {
    double ss = 0.0;
    for (double x : v) ss += (x - s.mean) * (x - s.mean);
    s.ci95_half = StudentT975(s.n - 1) * std::sqrt(ss / (s.n - 1)) / std::sqrt(static_cast<double>(s.n));
  }
  return s;
}

SweepFolder ReadSweepFolder(const std::string& dir) {
  namespace fs = std::filesystem;
  SweepFolder sw;
  sw.dir = dir;
  const std::string spec_path = (fs::path(dir) / "sweep.json").string();
  const nlohmann::json spec = ReadJsonFile(spec_path);
  auto strings = [&](const char* key) {
    std::vector<std::string> out;
    if (spec.contains(key) && spec.at(key).is_array())
      for (const auto& v : spec.at(key)) out.push_back(v.is_string() ? v.get<std::string>() : v.dump());
    return out;
  };
  sw.scenarios = strings("scenarios");
  sw.algorithms = strings("algorithms");
  if (spec.contains("grid") && spec.at("grid").is_object())
    for (const auto& [k, v] : spec.at("grid").items()) sw.grid_keys.push_back(k);

  const std::string csv_path = (fs::path(dir) / "results.csv").string();
  std::ifstream in(csv_path);
  if (!in) throw InputError(csv_path, 0, "cannot open results.csv", "re-run `slambox sweep` (or --resume)");
  std::string line;
  if (!std::getline(in, line)) throw InputError(csv_path, 1, "empty file", "re-run `slambox sweep`");
  const std::vector<std::string> header = SplitCsv(line);
  const std::vector<std::string> fixed{"run_id", "scenario", "seed", "algorithm", "status"};
  if (header.size() < fixed.size() || !std::equal(fixed.begin(), fixed.end(), header.begin()))
    throw InputError(csv_path, 1, "header must start with run_id,scenario,seed,algorithm,status",
                     "re-run `slambox sweep` with this version");
  for (size_t i = fixed.size(); i < header.size(); ++i)
    if (std::find(sw.grid_keys.begin(), sw.grid_keys.end(), header[i]) == sw.grid_keys.end())
      sw.metric_keys.push_back(header[i]);
  int line_no = 1;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty() || line == "\r") continue;
    const std::vector<std::string> cells = SplitCsv(line);
    if (cells.size() != header.size())
      throw InputError(csv_path, line_no, "row has " + std::to_string(cells.size()) + " cells, header has " +
                                              std::to_string(header.size()), "re-run `slambox sweep --resume`");
    SweepRow row;
    row.scenario = cells[1];
    row.algorithm = cells[3];
    row.status = cells[4];
    try {
      row.seed = cells[2].empty() ? 0 : std::stol(cells[2]);
      for (size_t i = fixed.size(); i < header.size(); ++i) {
        if (std::find(sw.grid_keys.begin(), sw.grid_keys.end(), header[i]) != sw.grid_keys.end())
          row.grid[header[i]] = cells[i];
        else
          row.metrics[header[i]] = cells[i].empty() ? NAN : std::stod(cells[i]);
      }
    } catch (const std::logic_error&) {
      throw InputError(csv_path, line_no, "a seed or metric cell is not a number", "re-run `slambox sweep --resume`");
    }
    sw.rows.push_back(std::move(row));
  }
  // Only algorithms that have rows (sweep.json may say `all`), in sweep.json's order, then
  // the rows' own order; the same fallback for scenarios.
  std::erase_if(sw.algorithms, [&](const std::string& a) {
    return std::none_of(sw.rows.begin(), sw.rows.end(), [&](const auto& r) { return r.algorithm == a; });
  });
  for (const auto& r : sw.rows) {
    if (std::find(sw.scenarios.begin(), sw.scenarios.end(), r.scenario) == sw.scenarios.end()) sw.scenarios.push_back(r.scenario);
    if (std::find(sw.algorithms.begin(), sw.algorithms.end(), r.algorithm) == sw.algorithms.end()) sw.algorithms.push_back(r.algorithm);
  }
  return sw;
}

}  // namespace slambox::render
