#include "app/sweep_check.hpp"

#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>
#include <tuple>

#include "eval/metrics.hpp"
#include "eval/statistics.hpp"

namespace slambox {

const CheckTolerance& CheckOptions::For(const std::string& metric) const {
  const auto it = per_metric.find(metric);
  return it == per_metric.end() ? tolerance : it->second;
}

namespace {

using RowKey = std::tuple<CellKey, std::uint64_t>;

std::string Number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

double ChangePercent(double base, double now) { return base != 0.0 ? 100.0 * (now / base - 1.0) : NAN; }

/// Worse in the metric's bad direction (both directions for a metric with none).
bool Worse(const MetricDescriptor& d, double base, double now, const CheckTolerance& tol) {
  const double margin = std::abs(base) * tol.relative + tol.absolute;
  switch (d.better) {
    case Better::kLower: return now > base + margin;
    case Better::kHigher: return now < base - margin;
    case Better::kNeither: return std::abs(now - base) > margin;
  }
  return false;
}

std::string Reproduce(const CellKey& cell, std::uint64_t seed) {
  std::string cmd = "slambox run " + cell.scenario + " --seed " + std::to_string(seed) + " --algo " + cell.algorithm;
  for (const auto& [k, v] : cell.grid) cmd += " --set " + k + "=" + v;
  return cmd + " -o out/repro";
}

std::vector<const MetricDescriptor*> CheckedMetrics() {
  std::vector<const MetricDescriptor*> out;
  for (const MetricDescriptor& d : MetricTable())
    if (d.checked) out.push_back(&d);
  return out;
}

// Every row of `baseline` against the current row of the same cell and seed.
void ComparePaired(const ResultsTable& current, const ResultsTable& baseline, const CheckOptions& options,
                   CheckReport& report) {
  std::map<RowKey, const ResultRow*> now;
  for (const ResultRow& r : current.rows) now[{CellOf(r), r.seed}] = &r;
  for (const ResultRow& b : baseline.rows) {
    const CellKey cell = CellOf(b);
    const std::string repro = Reproduce(cell, b.seed);
    ++report.compared;
    const auto it = now.find({cell, b.seed});
    if (it == now.end()) {
      report.regressions.push_back({cell.Text(), b.seed, "row", b.status, "missing", NAN, repro});
      continue;
    }
    const ResultRow& c = *it->second;
    if (b.status != "ok") continue;  // nothing to hold a failed baseline run to
    if (c.status != "ok") {
      report.regressions.push_back({cell.Text(), b.seed, "status", b.status, c.status, NAN, repro});
      continue;
    }
    for (const MetricDescriptor* d : CheckedMetrics()) {
      const auto bv = b.metrics.find(d->key);
      if (bv == b.metrics.end() || std::isnan(bv->second)) continue;
      const auto cv = c.metrics.find(d->key);
      const double base = bv->second, value = cv == c.metrics.end() ? NAN : cv->second;
      if (std::isnan(value))
        report.regressions.push_back({cell.Text(), b.seed, d->key, Number(base), "null", NAN, repro});
      else if (Worse(*d, base, value, options.For(d->key)))
        report.regressions.push_back(
            {cell.Text(), b.seed, d->key, Number(base), Number(value), ChangePercent(base, value), repro});
    }
  }
}

struct CellSummary {
  int rows = 0, ok = 0;
  std::uint64_t first_seed = 0;
  std::map<std::string, std::vector<double>> values;  ///< checked metrics over ok rows
};

std::map<CellKey, CellSummary> SummarizeCells(const ResultsTable& t) {
  std::map<CellKey, CellSummary> cells;
  for (const ResultRow& r : t.rows) {
    CellSummary& s = cells[CellOf(r)];
    if (s.rows++ == 0) s.first_seed = r.seed;
    if (r.status != "ok") continue;
    ++s.ok;
    for (const MetricDescriptor* d : CheckedMetrics()) {
      const auto it = r.metrics.find(d->key);
      if (it != r.metrics.end() && !std::isnan(it->second)) s.values[d->key].push_back(it->second);
    }
  }
  return cells;
}

// Cell means over the ok seeds (baselines recorded with other seeds), and ok-run counts.
void CompareCells(const ResultsTable& current, const ResultsTable& baseline, const CheckOptions& options,
                  CheckReport& report) {
  const auto now = SummarizeCells(current);
  for (const auto& [cell, b] : SummarizeCells(baseline)) {
    ++report.compared;
    const std::string repro = Reproduce(cell, b.first_seed);
    const auto it = now.find(cell);
    if (it == now.end()) {
      report.regressions.push_back({cell.Text(), std::nullopt, "cell", std::to_string(b.rows) + " rows", "missing",
                                    NAN, repro});
      continue;
    }
    const CellSummary& c = it->second;
    // Ok fractions: the seed counts may differ; fewer ok runs in proportion is a regression.
    if (static_cast<double>(c.ok) / c.rows < static_cast<double>(b.ok) / b.rows)
      report.regressions.push_back({cell.Text(), std::nullopt, "ok runs",
                                    std::to_string(b.ok) + "/" + std::to_string(b.rows),
                                    std::to_string(c.ok) + "/" + std::to_string(c.rows), NAN, repro});
    for (const auto& [key, base_values] : b.values) {
      const double base = Summarize(base_values).mean;
      const auto cv = c.values.find(key);
      if (cv == c.values.end() || cv->second.empty()) {
        report.regressions.push_back({cell.Text(), std::nullopt, key, Number(base), "null", NAN, repro});
        continue;
      }
      const double value = Summarize(cv->second).mean;
      if (Worse(*FindMetric(key), base, value, options.For(key)))
        report.regressions.push_back(
            {cell.Text(), std::nullopt, key, Number(base), Number(value), ChangePercent(base, value), repro});
    }
  }
}

}  // namespace

CheckReport CheckAgainstBaseline(const ResultsTable& current, const ResultsTable& baseline, const CheckOptions& options) {
  std::set<std::uint64_t> seeds_now, seeds_base;
  for (const ResultRow& r : current.rows) seeds_now.insert(r.seed);
  for (const ResultRow& r : baseline.rows) seeds_base.insert(r.seed);
  CheckReport report;
  report.paired = seeds_now == seeds_base;
  if (report.paired)
    ComparePaired(current, baseline, options, report);
  else
    CompareCells(current, baseline, options, report);
  return report;
}

std::string FormatCheckReport(const CheckReport& report, const std::string& baseline_path, const CheckOptions& options) {
  std::ostringstream out;
  const char* mode = report.paired ? "runs paired by seed" : "cell means (the seeds differ)";
  if (report.regressions.empty()) {
    out << "check: nothing got worse than " << baseline_path << " (" << report.compared << " " << mode
        << ", tolerance " << 100.0 * options.tolerance.relative << "% + " << options.tolerance.absolute << ")\n";
    return out.str();
  }
  out << "check: " << report.regressions.size() << " regression(s) against " << baseline_path << " (" << mode
      << ", tolerance " << 100.0 * options.tolerance.relative << "% + " << options.tolerance.absolute << "):\n";
  out << "  cell | seed | what | baseline -> now | change\n";
  for (const Regression& r : report.regressions) {
    out << "  " << r.cell << " | " << (r.seed ? std::to_string(*r.seed) : "all") << " | " << r.what << " | "
        << r.baseline << " -> " << r.current << " | ";
    if (std::isnan(r.change_percent)) out << "-";
    else out << (r.change_percent >= 0 ? "+" : "") << Number(r.change_percent) << "%";
    out << "\n";
  }
  out << "reproduce the first: " << report.regressions.front().reproduce << "\n";
  return out.str();
}

}  // namespace slambox
