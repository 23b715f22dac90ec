#include "app/sweep_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "eval/statistics.hpp"

namespace slambox {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Metrics shown in summary.md, in this order; lower is better for all but anees.
const std::vector<std::pair<std::string, std::string>> kSummaryMetrics = {
    {"ate_rmse_m", "ATE RMSE [m]"},         {"ate_aligned_rmse_m", "aligned ATE [m]"},
    {"rpe_trans_rmse_m", "RPE trans [m]"},  {"rpe_rot_rmse_deg", "RPE rot [deg]"},
    {"landmark_rmse_m", "landmarks [m]"},   {"anees", "ANEES"}};
const std::vector<std::string> kFixedColumns = {"run_id", "scenario", "seed", "algorithm", "status"};

bool IsErrorMetric(const std::string& key) {
  return key.rfind("ate_", 0) == 0 || key.rfind("rpe_", 0) == 0 || key == "landmark_rmse_m";
}

std::string Number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}


struct Table {
  CsvRow header;
  std::vector<CsvRow> rows;
  std::size_t Column(const std::string& name) const {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  }
};

Table LoadTable(const std::string& path) {
  if (!fs::exists(path)) throw InputError(path, 0, "no such results file", "give a results.csv written by slambox sweep");
  auto rows = ParseCsv(ReadText(path), path);
  if (rows.empty()) throw InputError(path, 1, "empty results file", "give a results.csv written by slambox sweep");
  Table t{rows.front(), {rows.begin() + 1, rows.end()}};
  for (const auto& c : kFixedColumns)
    if (t.Column(c) == t.header.size()) throw InputError(path, 1, "missing column '" + c + "'", "give a results.csv written by slambox sweep");
  return t;
}

// Cell key: every column that is neither a metric nor run-specific.
std::string CellKey(const Table& t, const CsvRow& row, const std::set<std::string>& grid_keys) {
  std::string key = row[t.Column("scenario")];
  for (std::size_t c = 0; c < t.header.size(); ++c)
    if (grid_keys.count(t.header[c])) key += " | " + t.header[c] + "=" + row[c];
  return key + " | " + row[t.Column("algorithm")];
}

std::set<std::string> GridColumns(const Table& t) {
  std::set<std::string> keys;  // grid keys are dotted scenario/algorithm keys; metrics never have dots
  for (const auto& h : t.header)
    if (h.find('.') != std::string::npos) keys.insert(h);
  return keys;
}

std::map<std::string, std::map<std::string, std::vector<double>>> CellValues(const Table& t) {
  const auto grid = GridColumns(t);
  std::map<std::string, std::map<std::string, std::vector<double>>> cells;
  for (const auto& row : t.rows) {
    auto& cell = cells[CellKey(t, row, grid)];
    for (std::size_t c = 0; c < t.header.size(); ++c) {
      if (!IsErrorMetric(t.header[c]) && t.header[c] != "anees") continue;
      if (row[c].empty() || row[t.Column("status")] != "ok") continue;
      cell[t.header[c]].push_back(std::stod(row[c]));
    }
  }
  return cells;
}

}  // namespace

bool IsTimingKey(const std::string& k) {
  return k.find("time") != std::string::npos || k.find("memory") != std::string::npos ||
         k.find("rss") != std::string::npos;
}

CellStats Summarize(std::vector<double> v) {
  CellStats s;
  s.n = static_cast<int>(v.size());
  if (v.empty()) return s;
  double sum = 0;
  for (double x : v) sum += x;
  s.mean = sum / s.n;
  double ss = 0;
  for (double x : v) ss += (x - s.mean) * (x - s.mean);
  s.std = s.n > 1 ? std::sqrt(ss / (s.n - 1)) : 0.0;
  std::sort(v.begin(), v.end());
  s.median = s.n % 2 ? v[s.n / 2] : 0.5 * (v[s.n / 2 - 1] + v[s.n / 2]);
  const double half = s.n > 1 ? StudentT975(s.n - 1) * s.std / std::sqrt(s.n) : 0.0;
  s.ci95_low = s.mean - half;
  s.ci95_high = s.mean + half;
  return s;
}

void WriteSweepSummary(const std::string& out_dir, const SweepSpec& spec, const std::vector<SweepRun>& runs) {
  // Gather each run's per-algorithm metrics (or its failure).
  struct Row { const SweepRun* run; std::string algorithm; json metrics; };
  std::vector<Row> rows;
  std::set<std::string> metric_keys, timing_keys;
  int missing = 0;
  for (const auto& run : runs) {
    const std::string dir = out_dir + "/runs/" + run.id;
    if (fs::exists(dir + "/metrics.json")) {
      const json doc = json::parse(ReadText(dir + "/metrics.json"));
      for (const auto& [algo, m] : doc.at("algorithms").items()) {
        rows.push_back({&run, algo, m});
        for (const auto& [k, v] : m.items()) {
          if (!v.is_number() && !v.is_null()) continue;
          (IsTimingKey(k) ? timing_keys : metric_keys).insert(k);
        }
      }
    } else if (fs::exists(dir + "/failed.json")) {
      for (const auto& algo : spec.algorithms) rows.push_back({&run, algo, json{{"status", "failed"}}});
    } else {
      ++missing;
    }
  }
  // Fixed DESIGN.md keys first, then the rest alphabetically (std::set order).
  std::vector<std::string> metrics;
  for (const auto& [k, label] : kSummaryMetrics)
    if (metric_keys.count(k)) metrics.push_back(k);
  for (const auto& k : metric_keys)
    if (std::find(metrics.begin(), metrics.end(), k) == metrics.end()) metrics.push_back(k);

  CsvRow header = kFixedColumns;
  for (const auto& [key, values] : spec.grid) header.push_back(key);
  header.insert(header.end(), metrics.begin(), metrics.end());
  std::string results = CsvLine(header);
  CsvRow timing_header = {"run_id", "algorithm"};
  timing_header.insert(timing_header.end(), timing_keys.begin(), timing_keys.end());
  std::string timing = CsvLine(timing_header);
  for (const auto& r : rows) {
    CsvRow line = {r.run->id, r.run->scenario, std::to_string(r.run->seed), r.algorithm,
                   r.metrics.value("status", "failed")};
    for (const auto& [key, value] : r.run->grid_values) line.push_back(value);
    auto value_of = [&](const std::string& k) {
      return r.metrics.contains(k) && r.metrics[k].is_number() ? Number(r.metrics[k].get<double>()) : std::string();
    };
    for (const auto& k : metrics) line.push_back(value_of(k));
    results += CsvLine(line);
    CsvRow t = {r.run->id, r.algorithm};
    for (const auto& k : timing_keys) t.push_back(value_of(k));
    timing += CsvLine(t);
  }
  WriteFileAtomic(out_dir + "/results.csv", results);
  WriteFileAtomic(out_dir + "/timing.csv", timing);

  // summary.md: one table per scenario, one row per cell.
  const Table table = LoadTable(out_dir + "/results.csv");
  const auto cells = CellValues(table);
  std::map<std::string, std::pair<int, int>> counts;  // cell -> (ok, all runs)
  const auto grid_columns = GridColumns(table);
  for (const auto& row : table.rows) {
    auto& [ok, all] = counts[CellKey(table, row, grid_columns)];
    ++all;
    ok += row[table.Column("status")] == "ok";
  }
  std::ostringstream md;
  md << "# Sweep summary\n\n" << runs.size() << " runs (" << spec.scenarios.size() << " scenarios x "
     << runs.size() / std::max<std::size_t>(1, spec.scenarios.size() * spec.seeds.size()) << " grid points x "
     << spec.seeds.size() << " seeds)";
  if (missing) md << "; **" << missing << " runs have no result yet** (resume the sweep)";
  md << ". Cells: mean ± std over seeds, median, 95% t-interval of the mean. Best mean per scenario in bold.\n";
  for (const auto& scenario : spec.scenarios) {
    md << "\n## " << scenario << "\n\n| algorithm | parameters | ok/runs |";
    for (const auto& [k, label] : kSummaryMetrics) md << " " << label << " |";
    md << "\n|---|---|---|";
    for (std::size_t i = 0; i < kSummaryMetrics.size(); ++i) md << "---|";
    md << "\n";
    std::map<std::string, double> best;  // metric -> best mean in this scenario
    for (const auto& [key, values] : cells) {
      if (key.rfind(scenario + " |", 0) != 0) continue;
      for (const auto& [metric, v] : values) {
        if (metric == "anees" || v.empty()) continue;
        const double m = Summarize(v).mean;
        if (!best.count(metric) || m < best[metric]) best[metric] = m;
      }
    }
    for (const auto& [key, values] : cells) {
      if (key.rfind(scenario + " |", 0) != 0) continue;
      const auto [ok, all] = counts[key];
      // key = "scenario | k=v | ... | algorithm"
      const std::string rest = key.substr(scenario.size() + 3);
      const auto last = rest.rfind(" | ");
      std::string params = last == std::string::npos ? "–" : rest.substr(0, last);
      for (std::size_t p; (p = params.find(" | ")) != std::string::npos;) params.replace(p, 3, ", ");
      md << "| " << (last == std::string::npos ? rest : rest.substr(last + 3)) << " | " << params << " | " << ok << "/"
         << all << " |";
      for (const auto& [metric, label] : kSummaryMetrics) {
        const auto it = values.find(metric);
        if (it == values.end() || it->second.empty()) { md << " – |"; continue; }
        const CellStats s = Summarize(it->second);
        char buf[160];
        std::snprintf(buf, sizeof buf, "%.4g ± %.2g (med %.4g, CI %.4g–%.4g)", s.mean, s.std, s.median, s.ci95_low, s.ci95_high);
        const bool bold = best.count(metric) && s.mean == best[metric];
        md << " " << (bold ? "**" : "") << buf << (bold ? "**" : "") << " |";
      }
      md << "\n";
    }
  }
  WriteFileAtomic(out_dir + "/summary.md", md.str());
}

std::vector<Regression> CheckBaseline(const std::string& results_csv, const std::string& baseline_csv,
                                      double tolerance, double tolerance_abs) {
  const auto current = CellValues(LoadTable(results_csv));
  const auto baseline = CellValues(LoadTable(baseline_csv));
  std::vector<Regression> out;
  for (const auto& [cell, metrics] : baseline) {
    for (const auto& [metric, base_values] : metrics) {
      if (!IsErrorMetric(metric) || base_values.empty()) continue;
      const double base = Summarize(base_values).mean;
      const auto c = current.find(cell);
      if (c == current.end() || !c->second.count(metric) || c->second.at(metric).empty()) {
        out.push_back({cell, metric, base, NAN});
        continue;
      }
      const double now = Summarize(c->second.at(metric)).mean;
      if (now > base * (1.0 + tolerance) + tolerance_abs) out.push_back({cell, metric, base, now});
    }
  }
  return out;
}

}  // namespace slambox
