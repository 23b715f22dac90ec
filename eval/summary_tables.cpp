#include "eval/summary_tables.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <sstream>

#include "eval/metrics.hpp"

namespace slambox {

namespace {

/// Decimals that show `v` to 3 significant digits (0 for |v| >= 100).
int Decimals(double v) {
  if (!(std::abs(v) > 0.0) || !std::isfinite(v)) return 0;
  return std::clamp(2 - static_cast<int>(std::floor(std::log10(std::abs(v)))), 0, 12);
}

std::string Fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

/// Display width of UTF-8 text (code points; "±", "–" count one).
size_t Width(const std::string& s) {
  return static_cast<size_t>(std::count_if(s.begin(), s.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

/// A Markdown pipe table with every column padded to its widest cell.
std::string Table(const std::vector<std::vector<std::string>>& rows) {
  std::vector<size_t> w;
  for (const auto& r : rows)
    for (size_t i = 0; i < r.size(); ++i) {
      if (w.size() <= i) w.push_back(3);
      w[i] = std::max(w[i], Width(r[i]));
    }
  std::string out;
  for (size_t k = 0; k < rows.size(); ++k) {
    out += "|";
    for (size_t i = 0; i < rows[k].size(); ++i) out += " " + rows[k][i] + std::string(w[i] - Width(rows[k][i]), ' ') + " |";
    out += "\n";
    if (k == 0) {
      out += "|";
      for (size_t i = 0; i < w.size(); ++i) out += std::string(w[i] + 2, '-') + "|";
      out += "\n";
    }
  }
  return out;
}

struct Cell {
  CellKey key;
  int ok = 0, all = 0;
  std::map<std::string, std::vector<double>> values;  ///< metric -> values of the ok runs
};

/// "sigma_range_m=0.01, laps=2": each swept key by its last part when those are distinct
/// (the full keys are in the caption line and results.csv), else in full.
std::string Params(const CellKey& key, const std::vector<std::string>& grid_keys) {
  auto last = [](const std::string& k) { return k.substr(k.rfind('.') + 1); };
  std::vector<std::string> parts;
  for (const auto& k : grid_keys) parts.push_back(last(k));
  std::sort(parts.begin(), parts.end());
  const bool short_names = std::adjacent_find(parts.begin(), parts.end()) == parts.end();
  std::string out;
  for (const auto& [k, v] : key.grid) out += (out.empty() ? "" : ", ") + (short_names ? last(k) : k) + "=" + v;
  return out.empty() ? "–" : out;
}

std::string IntervalText(const MeanInterval& iv) {
  const int d = std::max(Decimals(iv.lo), Decimals(iv.hi));
  return Fixed(iv.lo, d) + "–" + Fixed(iv.hi, d) + (iv.clipped ? " (clipped at 0)" : "");
}

}  // namespace

std::string FormatMeanStd(double mean, double std) {
  const int d = Decimals(mean != 0.0 ? mean : std);
  std::string s = Fixed(std, d);
  if (std > 0.0 && std::stod(s) == 0.0) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2g", std);
    s = buf;
  }
  return Fixed(mean, d) + " ± " + s;
}

std::vector<std::string> ScenariosOf(const ResultsTable& table) {
  std::vector<std::string> out;
  for (const auto& r : table.rows)
    if (std::find(out.begin(), out.end(), r.scenario) == out.end()) out.push_back(r.scenario);
  return out;
}

std::string SummaryCaption(IntervalMethod interval) {
  std::string iv;
  switch (interval) {
    case IntervalMethod::kAuto:
      iv = "a percentile bootstrap of the mean below 10 seeds (with 3 seeds it spans the lowest to the highest value), "
           "the Student-t interval from 10 seeds";
      break;
    case IntervalMethod::kStudentT: iv = "the Student-t interval of the mean, clipped at 0"; break;
    case IntervalMethod::kBootstrap: iv = "a percentile bootstrap of the mean"; break;
  }
  return "Each cell: mean ± std over the seeds whose run ended ok (3 significant digits; `2/3 ok` when runs failed "
         "or diverged); the best mean per scenario in bold; columns without any value left out. The collapsed table "
         "under each gives medians and 95 % intervals: " + iv + " (`interval:` in the sweep file).\n";
}

std::string ScenarioSummary(const ResultsTable& table, const std::string& scenario, IntervalMethod interval) {
  std::vector<Cell> cells;
  for (const ResultRow& row : table.rows) {
    if (row.scenario != scenario) continue;
    const CellKey key = CellOf(row);
    auto it = std::find_if(cells.begin(), cells.end(), [&](const Cell& c) { return c.key == key; });
    if (it == cells.end()) it = cells.insert(cells.end(), Cell{key, 0, 0, {}});
    ++it->all;
    if (row.status != "ok") continue;
    ++it->ok;
    for (const auto& [k, v] : row.metrics)
      if (!std::isnan(v)) it->values[k].push_back(v);
  }
  // Columns: summary.md's metrics that some cell of this scenario has a value of.
  std::vector<const MetricDescriptor*> shown;
  for (const MetricDescriptor* d : SummaryMetrics())
    if (std::any_of(cells.begin(), cells.end(), [&](const Cell& c) { return c.values.count(d->key); })) shown.push_back(d);
  const bool grid = !table.grid_keys.empty();
  std::map<std::string, double> best;  // metric -> best mean in this scenario
  for (const Cell& c : cells)
    for (const MetricDescriptor* d : shown) {
      const auto it = c.values.find(d->key);
      if (d->better == Better::kNeither || it == c.values.end()) continue;
      const double m = Summarize(it->second).mean;
      const bool lower = d->better == Better::kLower;
      if (!best.count(d->key) || (lower ? m < best[d->key] : m > best[d->key])) best[d->key] = m;
    }

  std::vector<std::vector<std::string>> main{{"algorithm"}}, detail{{"algorithm"}};
  if (grid) main[0].push_back("parameters"), detail[0].push_back("parameters");
  for (const MetricDescriptor* d : shown) main[0].push_back(d->label);
  for (const char* h : {"metric", "n", "median", "95 % interval of the mean"}) detail[0].push_back(h);
  std::vector<IntervalMethod> methods;
  for (const Cell& c : cells) {
    std::vector<std::string> row{c.key.algorithm};
    if (grid) row.push_back(Params(c.key, table.grid_keys));
    const std::string ok = c.ok < c.all ? std::to_string(c.ok) + "/" + std::to_string(c.all) + " ok" : "";
    for (const MetricDescriptor* d : shown) {
      const auto it = c.values.find(d->key);
      if (it == c.values.end()) {
        row.push_back(c.ok == 0 ? ok : "–");
        continue;
      }
      const SampleSummary s = Summarize(it->second);
      const bool bold = best.count(d->key) && s.mean == best[d->key];
      const std::string text = FormatMeanStd(s.mean, s.std) + (ok.empty() ? "" : " (" + ok + ")");
      row.push_back(bold ? "**" + text + "**" : text);
      const MeanInterval iv = IntervalOfMean(it->second, interval, /*nonnegative=*/true);  // RMSEs and ANEES
      methods.push_back(iv.method);
      std::vector<std::string> drow{c.key.algorithm};
      if (grid) drow.push_back(Params(c.key, table.grid_keys));
      drow.insert(drow.end(), {d->label, std::to_string(s.n), Fixed(s.median, Decimals(s.median)), IntervalText(iv)});
      detail.push_back(drow);
    }
    main.push_back(row);
  }
  std::string md = "## " + scenario + "\n\n" + Table(main);
  if (detail.size() > 1) {
    const bool mixed = std::adjacent_find(methods.begin(), methods.end(), std::not_equal_to<>()) != methods.end();
    const std::string how = mixed ? "bootstrap below 10 values, Student-t from 10"
                            : methods.front() == IntervalMethod::kBootstrap ? "percentile bootstrap"
                                                                             : "Student-t";
    std::string name;  // the summary line is HTML (GitHub and the report render it)
    for (char c : scenario) name += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
    md += "\n<details><summary>" + name + ": medians and 95 % intervals of the mean (" + how +
          ")</summary>\n\n" + Table(detail) + "\n</details>\n";
  }
  return md;
}

}  // namespace slambox
