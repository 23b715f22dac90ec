#include "eval/results_table.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/file_status.hpp"

namespace slambox {

const std::string* GridValue(const ResultRow& row, const std::string& key) {
  for (const auto& [k, v] : row.grid)
    if (k == key) return &v;
  return nullptr;
}

std::string CellKey::Text() const {
  std::string text = scenario;
  for (const auto& [k, v] : grid) text += " | " + k + "=" + v;
  return text + " | " + algorithm;
}

CellKey CellOf(const ResultRow& row) { return {row.scenario, row.grid, row.algorithm}; }

const std::vector<std::string>& ResultsFixedColumns() {
  static const std::vector<std::string> columns = {"run_id", "scenario", "seed", "algorithm", "status"};
  return columns;
}

std::string ResultNumber(double v) {
  if (std::isnan(v)) return "";
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

double AsWritten(double v) { return std::isnan(v) ? v : std::stod(ResultNumber(v)); }

std::string ResultsCsv(const ResultsTable& t) {
  CsvRow header = ResultsFixedColumns();
  header.insert(header.end(), t.grid_keys.begin(), t.grid_keys.end());
  header.insert(header.end(), t.metric_keys.begin(), t.metric_keys.end());
  std::string out = CsvLine(header);
  for (const ResultRow& r : t.rows) {
    CsvRow line = {r.run_id, r.scenario, std::to_string(r.seed), r.algorithm, r.status};
    for (const auto& k : t.grid_keys) {
      const std::string* v = GridValue(r, k);
      line.push_back(v ? *v : "");
    }
    for (const auto& k : t.metric_keys) {
      const auto it = r.metrics.find(k);
      line.push_back(it == r.metrics.end() ? "" : ResultNumber(it->second));
    }
    out += CsvLine(line);
  }
  return out;
}

ResultsTable ReadResultsCsv(const std::string& path) {
  const std::string fix = "give a results.csv written by `slambox sweep` (or re-run it with --resume)";
  std::ifstream in(path, std::ios::binary);
  if (!IsRegularFile(path) || !in) throw InputError(path, 0, "no such results file", fix);
  std::stringstream text;
  text << in.rdbuf();
  const std::vector<CsvRow> rows = ParseCsv(text.str(), path);
  if (rows.empty()) throw InputError(path, 1, "empty results file", fix);
  const CsvRow& header = rows.front();
  const auto& fixed = ResultsFixedColumns();
  if (header.size() < fixed.size() || !std::equal(fixed.begin(), fixed.end(), header.begin()))
    throw InputError(path, 1, "the header must start with run_id,scenario,seed,algorithm,status", fix);
  ResultsTable t;
  for (std::size_t c = fixed.size(); c < header.size(); ++c)
    (header[c].find('.') != std::string::npos ? t.grid_keys : t.metric_keys).push_back(header[c]);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const CsvRow& cells = rows[i];
    ResultRow r;
    r.run_id = cells[0];
    r.scenario = cells[1];
    r.algorithm = cells[3];
    r.status = cells[4];
    try {
      std::size_t used = 0;
      r.seed = cells[2].empty() ? 0 : std::stoull(cells[2], &used);
      if (used != cells[2].size()) throw std::invalid_argument("seed");
      for (std::size_t c = fixed.size(); c < header.size(); ++c) {
        if (header[c].find('.') != std::string::npos) {
          r.grid.emplace_back(header[c], cells[c]);
          continue;
        }
        double v = NAN;
        if (!cells[c].empty()) {
          v = std::stod(cells[c], &used);
          if (used != cells[c].size()) throw std::invalid_argument(header[c]);
        }
        r.metrics[header[c]] = v;
      }
    } catch (const std::logic_error&) {
      // Rows are one line each (no field of results.csv holds a newline): row i is line i + 1.
      throw InputError(path, static_cast<int>(i + 1), "a seed or metric cell is not a number", fix);
    }
    t.rows.push_back(std::move(r));
  }
  return t;
}

}  // namespace slambox
