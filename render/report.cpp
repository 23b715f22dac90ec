#include "render/report.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/json_io.hpp"
#include "eval/metrics.hpp"
#include "eval/summary_tables.hpp"
#include "render/run_folder.hpp"
#include "render/run_pictures.hpp"
#include "render/sweep_folder.hpp"

namespace slambox::render {

namespace fs = std::filesystem;

namespace {

std::string Slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string Cell(const nlohmann::json& v) {
  if (v.is_null()) return "\u2014";
  if (v.is_number_integer()) return std::to_string(v.get<long>());
  if (v.is_number()) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v.get<double>());
    return buf;
  }
  if (v.is_string()) return v.get<std::string>();
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_array()) {
    std::string out = "[";
    for (const auto& x : v) out += (out.size() > 1 ? ", " : "") + Cell(x);
    return out + "]";
  }
  return v.dump();
}

std::string Escape(const std::string& s) {
  std::string out;
  for (char c : s)
    out += c == '&' ? "&amp;" : c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '"' ? "&quot;" : std::string(1, c);
  return out;
}

/// Figures of the folder in reading order: the overview first, then alphabetical.
std::vector<std::string> FigureFiles(const std::string& dir) {
  std::vector<std::string> names;
  const fs::path figs = fs::path(dir) / "figures";
  if (!fs::exists(figs)) return names;
  for (const auto& e : fs::directory_iterator(figs))
    if (e.path().extension() == ".png") names.push_back(e.path().stem().string());
  const std::vector<std::string> first{"trajectories", "error_distance", "nees"};
  std::sort(names.begin(), names.end(), [&](const std::string& a, const std::string& b) {
    const auto ia = std::find(first.begin(), first.end(), a) - first.begin();
    const auto ib = std::find(first.begin(), first.end(), b) - first.begin();
    return ia != ib ? ia < ib : a < b;
  });
  return names;
}

std::string FiguresSection(const std::string& dir) {
  std::string md = "\n## Figures\n\nEach figure is also written as SVG next to the PNG (figures/NAME.svg).\n\n";
  for (const auto& n : FigureFiles(dir)) md += "![" + n + "](figures/" + n + ".png)\n\n";
  return md;
}

std::string RunReport(const std::string& dir) {
  const nlohmann::json m = ReadJsonFile((fs::path(dir) / "metrics.json").string());
  std::string md = "# slambox run report\n\n";
  const bool log = m.value("converted_log", false);
  const nlohmann::json distance = m.value("distance_m", nlohmann::json());  // null: no ground truth
  md += (log ? "Log **" : "Scenario **") + Cell(m.value("scenario", nlohmann::json())) +
        (log ? "**" : "**, seed " + Cell(m.value("seed", nlohmann::json()))) + ", duration " +
        Cell(m.value("duration_s", nlohmann::json())) + " s" +
        (distance.is_number() ? ", distance travelled " + Cell(distance) + " m" : std::string()) + " (slambox " +
        Cell(m.value("slambox_version", nlohmann::json())) + ").\n\n";
  md += "## Metrics\n\n";
  // Each entry read through the typed record, shown as metrics.json holds it.
  const std::string metrics_path = (fs::path(dir) / "metrics.json").string();
  const nlohmann::json entries = m.value("algorithms", nlohmann::json::object());
  nlohmann::json algos = nlohmann::json::object();
  for (const auto& [name, entry] : entries.items()) algos[name] = ToJson(MetricsFromJson(entry, metrics_path));
  // Headline table: one row per module, the metric table's headline keys in its order.
  // Then every other key, transposed (one row per metric), in order of appearance.
  std::vector<std::string> shown, all;
  auto present = [&](const std::string& key) {
    for (const auto& [name, entry] : algos.items())
      if (entry.contains(key)) return true;
    return false;
  };
  for (const auto& d : MetricTable())
    if (d.headline && present(d.key)) shown.push_back(d.key);
  for (const auto& [name, entry] : algos.items())
    for (const auto& [k, v] : entry.items())
      if (std::find(shown.begin(), shown.end(), k) == shown.end() && std::find(all.begin(), all.end(), k) == all.end())
        all.push_back(k);
  auto cell = [](const nlohmann::json& entry, const std::string& key) {
    return entry.is_object() && entry.contains(key) ? Cell(entry.at(key)) : std::string("\u2014");
  };
  md += "| algorithm |";
  for (const auto& c : shown) md += " " + c + " |";
  md += "\n|---|";
  for (size_t i = 0; i < shown.size(); ++i) md += "---|";
  md += "\n";
  for (const auto& [name, entry] : algos.items()) {
    md += "| " + name + " |";
    for (const auto& c : shown) md += " " + cell(entry, c) + " |";
    md += "\n";
  }
  if (!all.empty()) {
    md += "\n### All metrics\n\n| metric |";
    for (const auto& [name, entry] : algos.items()) md += " " + name + " |";
    md += "\n|---|";
    for (size_t i = 0; i < algos.size(); ++i) md += "---|";
    md += "\n";
    for (const auto& c : all) {
      md += "| " + c + " |";
      for (const auto& [name, entry] : algos.items()) md += " " + cell(entry, c) + " |";
      md += "\n";
    }
  }
  md += "\nATE: absolute position error at matched timestamps (no alignment); RPE over 1 m of travel; "
        "ANEES: average pose NEES (\u2014 where the module has no covariance).\n";
  return md + FiguresSection(dir);
}

std::size_t SeedCount(const SweepFolder& sw) {
  std::set<std::uint64_t> seeds;
  for (const auto& r : sw.results.rows) seeds.insert(r.seed);
  return seeds.size();
}

/// What a sweep figure shows, from its file stem (render/figures_sweep.cpp names them).
std::string SweepFigureCaption(const SweepFolder& sw, const std::string& stem) {
  auto label = [](const std::string& key) {
    const MetricDescriptor* d = FindMetric(key);
    return d ? d->label : key;
  };
  const std::string seeds = std::to_string(SeedCount(sw)) + " seeds";
  if (stem.rfind("box_", 0) == 0)
    return label(stem.substr(4)) + " per module and scenario over " + seeds +
           (sw.results.grid_keys.empty() ? "" : " and every grid point") +
           ": box = quartiles, thick line = median, whiskers = the last values within 1.5 IQR, rings = outliers";
  if (stem.rfind("vs_", 0) == 0)
    return "ATE RMSE [m] against " + stem.substr(3) + ": mean and 95 % interval of the mean over " + seeds + " (" +
           IntervalMethodName(sw.interval) + ")";
  if (stem.rfind("heatmap_", 0) == 0)
    return "Mean ATE RMSE [m] of " + stem.substr(8) + " over the first two swept keys (" + seeds + ")";
  return stem;
}

std::string SweepReport(const std::string& dir) {
  const SweepFolder sw = ReadSweepFolder(dir);
  const nlohmann::json spec = ReadJsonFile((fs::path(dir) / "sweep.json").string());
  std::string md = "# slambox sweep report\n\n";
  std::string modules;
  for (const auto& a : sw.algorithms) modules += (modules.empty() ? "" : ", ") + a;
  md += std::to_string(sw.scenarios.size()) + " scenarios x " + std::to_string(sw.algorithms.size()) + " modules (" +
        modules + ") x " + std::to_string(SeedCount(sw)) + " seeds" +
        (sw.results.grid_keys.empty() ? "" : "; grid: " + spec.value("grid", nlohmann::json::object()).dump()) +
        ". Per-run results: results.csv; these tables as plain text: summary.md.\n\n";
  md += "## Contents\n\n";
  for (const auto& s : sw.scenarios) md += "- [" + s + "](#" + HeadingId(s) + ")\n";
  const std::vector<std::string> figures = FigureFiles(dir);
  if (!figures.empty()) md += "- [All scenarios](#" + HeadingId("All scenarios") + ")\n";
  md += "\n" + SummaryCaption(sw.interval) + "\n";
  for (const auto& scenario : sw.scenarios) {
    md += ScenarioSummary(sw.results, scenario, sw.interval);
    // Pictures of each grid point: its representative seed's run.
    std::vector<std::pair<GridValues, std::vector<const ResultRow*>>> cells;
    for (const auto& r : sw.results.rows) {
      if (r.scenario != scenario) continue;
      auto it = std::find_if(cells.begin(), cells.end(), [&](const auto& c) { return c.first == r.grid; });
      if (it == cells.end()) it = cells.insert(cells.end(), {r.grid, {}});
      it->second.push_back(&r);
    }
    std::string pictures;
    for (const auto& [grid, rows] : cells) {
      const Representative rep = RepresentativeRun(rows);
      const fs::path pics = fs::path(dir) / "runs" / rep.run_id / kPicturesDir;
      if (rep.run_id.empty() || !fs::is_directory(pics)) continue;
      std::string where = scenario;
      for (const auto& [k, v] : grid) where += ", " + k + "=" + v;
      const std::string which = "seed " + std::to_string(rep.seed) +
                                (rep.seeds > 1 ? " (the median of " + std::to_string(rep.seeds) +
                                                     " seeds by each module's ATE rank)" : "");
      std::vector<std::string> stems;
      if (fs::exists(pics / "trajectories.png")) stems.push_back("trajectories");
      for (const auto& a : sw.algorithms)
        if (fs::exists(pics / ("map_" + SafeFileName(a) + ".png"))) stems.push_back("map_" + SafeFileName(a));
      for (const auto& stem : stems) {
        const std::string what = stem == "trajectories"
                                     ? where + ": the world, ground truth (black) and every module's path, " + which
                                     : where + ": the map " + stem.substr(4) + " built, " + which;
        pictures += "![" + what + "](runs/" + rep.run_id + "/" + kPicturesDir + "/" + stem + ".png)\n";
      }
    }
    md += pictures.empty() ? "\nNo pictures of this scenario's runs (the sweep ran with --no-figures).\n"
                           : "\n" + pictures;
    md += "\n";
  }
  if (!figures.empty()) {
    md += "## All scenarios\n\nEach figure is also written as SVG next to the PNG (figures/NAME.svg).\n\n";
    for (const auto& n : figures) md += "![" + SweepFigureCaption(sw, n) + "](figures/" + n + ".png)\n";
  }
  return md;
}

/// **bold**, `code` and [text](#anchor) links; everything else escaped.
std::string Inline(const std::string& text) {
  std::string out;
  bool bold = false, code = false;
  for (size_t i = 0; i < text.size(); ++i) {
    if (!code && text.compare(i, 2, "**") == 0) {
      out += bold ? "</b>" : "<b>";
      bold = !bold;
      ++i;
    } else if (text[i] == '`') {
      out += code ? "</code>" : "<code>";
      code = !code;
    } else if (!code && text[i] == '[' && text.find("](#", i) != std::string::npos) {
      const size_t mid = text.find("](#", i), end = text.find(')', mid);
      if (end == std::string::npos || text.find('[', i + 1) < mid) {
        out += "[";
        continue;
      }
      out += "<a href=\"#" + Escape(text.substr(mid + 3, end - mid - 3)) + "\">" + Escape(text.substr(i + 1, mid - i - 1)) +
             "</a>";
      i = end;
    } else {
      out += Escape(std::string(1, text[i]));
    }
  }
  if (code) out += "</code>";
  if (bold) out += "</b>";
  return out;
}

}  // namespace

std::string Base64(const std::string& bytes) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const unsigned b0 = static_cast<unsigned char>(bytes[i]);
    const unsigned b1 = i + 1 < bytes.size() ? static_cast<unsigned char>(bytes[i + 1]) : 0;
    const unsigned b2 = i + 2 < bytes.size() ? static_cast<unsigned char>(bytes[i + 2]) : 0;
    const unsigned v = (b0 << 16) | (b1 << 8) | b2;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kAlphabet[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kAlphabet[v & 63] : '=';
  }
  return out;
}

std::string HeadingId(const std::string& heading) {
  std::string id;
  for (unsigned char c : heading) {
    if (std::isalnum(c)) id += static_cast<char>(std::tolower(c));
    else if (!id.empty() && id.back() != '-') id += '-';
  }
  while (!id.empty() && id.back() == '-') id.pop_back();
  return id.empty() ? "section" : id;
}

std::string MarkdownToHtml(const std::string& md, const std::string& base_dir) {
  // Readable at 1400 px and on a phone: the text column is capped, wide tables scroll
  // inside their box (the page itself never scrolls sideways), figures shrink to the
  // column and sit two abreast where there is room.
  std::string html =
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>slambox report</title>\n<style>"
      "body{font-family:'DejaVu Sans',sans-serif;max-width:1300px;margin:1.5em auto;padding:0 1em;color:#222;"
      "line-height:1.4}"
      "h1{font-size:1.6em}h2{font-size:1.3em;margin-top:1.8em;border-bottom:1px solid #ccc}"
      ".table{overflow-x:auto;max-width:100%}"
      "table{border-collapse:collapse;margin:0.6em 0;font-variant-numeric:tabular-nums}"
      "td,th{border:1px solid #bbb;padding:3px 8px;text-align:right;white-space:nowrap}"
      "td:first-child,th:first-child{text-align:left}th{background:#eee}"
      "details{margin:0.5em 0}summary{cursor:pointer;color:#444}"
      ".figs{display:flex;flex-wrap:wrap;gap:1em;margin:0.8em 0}"
      "figure{margin:0;flex:1 1 560px;max-width:100%}.figs figure:only-child{flex-basis:100%}"
      "img{max-width:100%;height:auto;display:block}figcaption{font-size:0.9em;color:#444;margin-top:0.3em}"
      "code{background:#f3f3f3;padding:0 3px}"
      "@media (max-width:700px){body{margin:0.5em auto;padding:0 0.5em;font-size:15px}td,th{padding:2px 5px}"
      "figure{flex-basis:100%}}"
      "</style></head><body>\n";
  std::istringstream in(md);
  std::string line, para;
  bool in_table = false, header_row = false, in_list = false, in_figs = false;
  auto flush = [&] {
    if (!para.empty()) html += "<p>" + Inline(para) + "</p>\n";
    para.clear();
  };
  // Close whatever block `next` does not continue.
  auto close = [&](const char* next) {
    const std::string n = next;
    if (in_table && n != "table") html += "</table></div>\n", in_table = false;
    if (in_list && n != "list") html += "</ul>\n", in_list = false;
    if (in_figs && n != "figure") html += "</div>\n", in_figs = false;
  };
  while (std::getline(in, line)) {
    if (line.rfind("|", 0) == 0) {
      flush();
      close("table");
      if (!in_table) { html += "<div class=\"table\"><table>\n"; in_table = true; header_row = true; }
      if (line.find("---") != std::string::npos && line.find_first_not_of("|- ") == std::string::npos) continue;
      std::vector<std::string> cells;
      std::stringstream ss(line.substr(1));
      std::string cell;
      while (std::getline(ss, cell, '|')) cells.push_back(cell);
      if (!cells.empty() && cells.back().find_first_not_of(" \t\r") == std::string::npos) cells.pop_back();
      html += "<tr>";
      for (auto& c : cells) {
        const auto a = c.find_first_not_of(' '), b = c.find_last_not_of(' ');
        c = a == std::string::npos ? "" : c.substr(a, b - a + 1);
        html += (header_row ? "<th>" : "<td>") + Inline(c) + (header_row ? "</th>" : "</td>");
      }
      html += "</tr>\n";
      header_row = false;
      continue;
    }
    if (line.rfind("<details>", 0) == 0 || line.rfind("</details>", 0) == 0) {  // written by us: passed as is
      flush();
      close("");
      html += line + "\n";
      continue;
    }
    if (line.rfind("- ", 0) == 0) {
      flush();
      close("list");
      if (!in_list) html += "<ul>\n", in_list = true;
      html += "<li>" + Inline(line.substr(2)) + "</li>\n";
      continue;
    }
    if (line.rfind("![", 0) == 0 && line.find("](") != std::string::npos) {
      flush();
      close("figure");
      const size_t mid = line.find("](");
      const std::string alt = line.substr(2, mid - 2), path = line.substr(mid + 2, line.find(')', mid) - mid - 2);
      const fs::path file = fs::path(base_dir) / path;
      if (!fs::exists(file)) continue;
      if (!in_figs) html += "<div class=\"figs\">\n", in_figs = true;
      html += "<figure><img alt=\"" + Escape(alt) + "\" src=\"data:image/png;base64," + Base64(Slurp(file)) +
              "\"><figcaption>" + Inline(alt) + "</figcaption></figure>\n";
      continue;
    }
    if (line.empty()) {
      flush();
      if (in_table) close("");
      continue;
    }
    close("");
    if (line[0] == '#') {
      flush();
      const size_t level = std::min<size_t>(6, line.find_first_not_of('#'));
      const std::string text = line.substr(std::min(line.size(), level + 1));
      const std::string h = std::to_string(level);
      html += "<h" + h + " id=\"" + HeadingId(text) + "\">" + Inline(text) + "</h" + h + ">\n";
      continue;
    }
    para += (para.empty() ? "" : " ") + line;
  }
  flush();
  close("");
  return html + "</body></html>\n";
}

FolderKind DetectFolder(const std::string& dir) {
  if (fs::exists(fs::path(dir) / "metrics.json")) return FolderKind::kRun;
  if (fs::exists(fs::path(dir) / "sweep.json")) return FolderKind::kSweep;
  throw InputError(dir, 0, "neither a run folder (metrics.json) nor a sweep folder (sweep.json)",
                   "pass a folder written by `slambox run -o DIR` or `slambox sweep -o DIR`");
}

void WriteReport(const std::string& dir) {
  const std::string md = DetectFolder(dir) == FolderKind::kRun ? RunReport(dir) : SweepReport(dir);
  WriteFileAtomic((fs::path(dir) / "report.md").string(), md);
  WriteFileAtomic((fs::path(dir) / "report.html").string(), MarkdownToHtml(md, dir));
}

}  // namespace slambox::render
