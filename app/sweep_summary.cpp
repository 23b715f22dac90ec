#include "app/sweep_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/csv.hpp"
#include "core/error.hpp"
#include "core/file_status.hpp"
#include "core/json_io.hpp"
#include "eval/metrics.hpp"
#include "eval/statistics.hpp"
#include "eval/summary_tables.hpp"

namespace slambox {

namespace fs = std::filesystem;


void WriteSweepSummary(const std::string& out_dir, const SweepSpec& spec, const std::vector<SweepRun>& runs) {
  // Gather each run's per-algorithm metrics (or its failure).
  struct Entry {
    const SweepRun* run;
    std::string algorithm;
    Metrics metrics;
  };
  std::vector<Entry> entries;
  int missing = 0;
  for (const auto& run : runs) {
    const std::string dir = out_dir + "/runs/" + run.id;
    if (PathExists(dir + "/metrics.json")) {
      const std::string path = dir + "/metrics.json";
      const nlohmann::json doc = ReadJsonFile(path);
      if (!doc.contains("algorithms") || !doc.at("algorithms").is_object())
        throw InputError(path, 0, "no \"algorithms\" object", "re-run the sweep with --resume after deleting the run");
      for (const auto& [algo, m] : doc.at("algorithms").items()) entries.push_back({&run, algo, MetricsFromJson(m, path)});
    } else if (PathExists(dir + "/failed.json")) {
      for (const auto& algo : spec.algorithms)
        entries.push_back({&run, algo, UnscoredMetrics(RunStatus::kFailed)});
    } else {
      ++missing;
    }
  }
  // A metric is a column when some entry has it as a number or null.
  std::set<std::string> metric_keys, timing_keys;
  for (const auto& e : entries)
    for (const auto& d : MetricTable()) {
      const nlohmann::json v = MetricValue(d, e.metrics);
      if (v.is_number() || v.is_null()) (d.timing ? timing_keys : metric_keys).insert(d.key);
    }
  // summary.md's metrics first, then the rest alphabetically (std::set order).
  ResultsTable table;
  for (const MetricDescriptor* d : SummaryMetrics())
    if (metric_keys.count(d->key)) table.metric_keys.push_back(d->key);
  for (const auto& k : metric_keys)
    if (std::find(table.metric_keys.begin(), table.metric_keys.end(), k) == table.metric_keys.end())
      table.metric_keys.push_back(k);
  for (const auto& [key, values] : spec.grid) table.grid_keys.push_back(key);

  CsvRow timing_header = {"run_id", "algorithm"};
  timing_header.insert(timing_header.end(), timing_keys.begin(), timing_keys.end());
  std::string timing = CsvLine(timing_header);
  for (const auto& e : entries) {
    ResultRow row{.run_id = e.run->id, .scenario = e.run->scenario, .seed = e.run->seed, .algorithm = e.algorithm,
                  .status = RunStatusName(e.metrics.status), .grid = e.run->grid_values, .metrics = {}};
    for (const auto& k : table.metric_keys) row.metrics[k] = AsWritten(MetricNumber(*FindMetric(k), e.metrics));
    table.rows.push_back(std::move(row));
    CsvRow t = {e.run->id, e.algorithm};
    for (const auto& k : timing_keys) t.push_back(ResultNumber(MetricNumber(*FindMetric(k), e.metrics)));
    timing += CsvLine(t);
  }
  WriteFileAtomic(out_dir + "/results.csv", ResultsCsv(table));
  WriteFileAtomic(out_dir + "/timing.csv", timing);
  WriteFileAtomic(out_dir + "/summary.md", SummaryMarkdown(table, spec, runs.size(), missing));
}

std::string SummaryMarkdown(const ResultsTable& table, const SweepSpec& spec, std::size_t runs, int missing) {
  std::ostringstream md;
  md << "# Sweep summary\n\n" << runs << " runs (" << spec.scenarios.size() << " scenarios x "
     << runs / std::max<std::size_t>(1, spec.scenarios.size() * spec.seeds.size()) << " grid points x "
     << spec.seeds.size() << " seeds)";
  if (missing) md << "; **" << missing << " runs have no result yet** (resume the sweep)";
  md << ". " << SummaryCaption(spec.interval);
  if (!table.grid_keys.empty()) {
    md << "Swept (the `parameters` column names each by its last part):";
    for (const auto& k : table.grid_keys) md << " `" << k << "`";
    md << ".\n";
  }
  for (const auto& scenario : ScenariosOf(table)) md << "\n" << ScenarioSummary(table, scenario, spec.interval);
  return md.str();
}

}  // namespace slambox
