#include "render/report.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/json_io.hpp"
#include "eval/metrics.hpp"
#include "render/run_folder.hpp"

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
  for (char c : s) out += c == '&' ? "&amp;" : c == '<' ? "&lt;" : c == '>' ? "&gt;" : std::string(1, c);
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
  md += "Scenario **" + Cell(m.value("scenario", nlohmann::json())) + "**, seed " + Cell(m.value("seed", nlohmann::json())) +
        ", duration " + Cell(m.value("duration_s", nlohmann::json())) + " s, distance travelled " +
        Cell(m.value("distance_m", nlohmann::json())) + " m (slambox " + Cell(m.value("slambox_version", nlohmann::json())) + ").\n\n";
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

std::string SweepReport(const std::string& dir) {
  const nlohmann::json spec = ReadJsonFile((fs::path(dir) / "sweep.json").string());
  std::string md = "# slambox sweep report\n\n";
  md += "Scenarios: " + spec.value("scenarios", nlohmann::json::array()).dump() +
        "; algorithms: " + spec.value("algorithms", nlohmann::json::array()).dump() +
        "; seeds: " + spec.value("seeds", nlohmann::json()).dump() +
        "; grid: " + spec.value("grid", nlohmann::json::object()).dump() + ".\n\nPer-run results: results.csv.\n\n";
  const fs::path summary = fs::path(dir) / "summary.md";
  if (fs::exists(summary)) {
    std::string s = Slurp(summary);
    // Demote the summary's headings one level under this report's title.
    std::istringstream in(s);
    std::string line, demoted;
    while (std::getline(in, line)) demoted += (line.rfind("#", 0) == 0 ? "#" + line : line) + "\n";
    md += demoted + "\n";
  }
  return md + FiguresSection(dir);
}

std::string Inline(const std::string& text) {
  // **bold** only; everything else escaped.
  std::string out, esc = Escape(text);
  bool open = false;
  for (size_t i = 0; i < esc.size(); ++i) {
    if (esc.compare(i, 2, "**") == 0) {
      out += open ? "</b>" : "<b>";
      open = !open;
      ++i;
    } else {
      out += esc[i];
    }
  }
  if (open) out += "</b>";
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

std::string MarkdownToHtml(const std::string& md, const std::string& base_dir) {
  std::string html =
      "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>slambox report</title>\n<style>"
      "body{font-family:'DejaVu Sans',sans-serif;max-width:1250px;margin:2em auto;padding:0 1em;color:#222}"
      "table{border-collapse:collapse;margin:1em 0}td,th{border:1px solid #bbb;padding:4px 8px;text-align:right}"
      "td:first-child,th:first-child{text-align:left}th{background:#eee}img{max-width:100%;margin:0.5em 0 1.5em}"
      "</style></head><body>\n";
  std::istringstream in(md);
  std::string line, para;
  bool in_table = false, header_row = false;
  auto flush = [&] {
    if (!para.empty()) html += "<p>" + Inline(para) + "</p>\n";
    para.clear();
  };
  while (std::getline(in, line)) {
    if (line.rfind("|", 0) == 0) {
      flush();
      if (!in_table) { html += "<table>\n"; in_table = true; header_row = true; }
      if (line.find("---") != std::string::npos) continue;  // the separator row
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
    if (in_table) { html += "</table>\n"; in_table = false; }
    if (line.empty()) { flush(); continue; }
    if (line[0] == '#') {
      flush();
      const size_t level = std::min<size_t>(6, line.find_first_not_of('#'));
      const std::string text = line.substr(std::min(line.size(), level + 1));
      html += "<h" + std::to_string(level) + ">" + Inline(text) + "</h" + std::to_string(level) + ">\n";
      continue;
    }
    if (line.rfind("![", 0) == 0 && line.find("](") != std::string::npos) {
      flush();
      const size_t mid = line.find("](");
      const std::string alt = line.substr(2, mid - 2), path = line.substr(mid + 2, line.find(')', mid) - mid - 2);
      const fs::path file = fs::path(base_dir) / path;
      if (fs::exists(file))
        html += "<figure><img alt=\"" + Escape(alt) + "\" src=\"data:image/png;base64," + Base64(Slurp(file)) +
                "\"><figcaption>" + Escape(alt) + "</figcaption></figure>\n";
      continue;
    }
    para += (para.empty() ? "" : " ") + line;
  }
  flush();
  if (in_table) html += "</table>\n";
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
