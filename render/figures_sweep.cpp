// Sweep figures. Each point of a sweep is a metric eval computed per run (results.csv);
// here they are only summarized for display (quartiles, means, 95% intervals).
#include "render/figures_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "eval/metrics.hpp"
#include "eval/statistics.hpp"
#include "render/legend.hpp"
#include "render/sweep_folder.hpp"

namespace slambox::render {

namespace {

const FigureStyle kStyle{};

namespace fs = std::filesystem;

std::string Safe(std::string s) {
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '_';
  return s;
}

std::string MetricLabel(const std::string& key) {
  const MetricDescriptor* d = FindMetric(key);
  return d ? d->label : key;
}

std::vector<double> Values(const SweepFolder& sw, const std::string& metric, auto&& keep) {
  std::vector<double> out;
  for (const auto& r : sw.results.rows)
    if (r.status == "ok" && keep(r) && r.metrics.count(metric)) out.push_back(r.metrics.at(metric));
  return out;
}

std::vector<std::string> PrimaryMetrics(const SweepFolder& sw) {
  std::vector<std::string> out;
  const auto& keys = sw.results.metric_keys;
  for (const char* m : {"ate_rmse_m", "rpe_trans_rmse_m"})
    if (std::find(keys.begin(), keys.end(), m) != keys.end()) out.push_back(m);
  if (out.empty() && !keys.empty()) out.push_back(keys.front());
  return out;
}

bool BoxFigure(const SweepFolder& sw, const std::string& metric, const std::string& stem) {
  std::vector<std::vector<SampleSummary>> stats(sw.scenarios.size(), std::vector<SampleSummary>(sw.algorithms.size()));
  double lo = INFINITY, hi = -INFINITY;
  for (size_t s = 0; s < sw.scenarios.size(); ++s)
    for (size_t a = 0; a < sw.algorithms.size(); ++a) {
      stats[s][a] = Summarize(Values(sw, metric, [&](const ResultRow& r) {
        return r.scenario == sw.scenarios[s] && r.algorithm == sw.algorithms[a];
      }));
      const SampleSummary& g = stats[s][a];
      if (g.n == 0) continue;
      lo = std::min({lo, g.whisker_lo, g.outliers.empty() ? g.whisker_lo : *std::min_element(g.outliers.begin(), g.outliers.end())});
      hi = std::max({hi, g.whisker_hi, g.outliers.empty() ? g.whisker_hi : *std::max_element(g.outliers.begin(), g.outliers.end())});
    }
  if (!(lo <= hi)) return false;
  Canvas c(1300, 660, 3);  // the legend sits right of the plot, never over a box
  const PlotArea area{112, 62, 1300 - 230, 660 - 110};
  // Errors spanning more than two decades (a diverged baseline beside cm-level SLAM) go
  // on a log axis, so the small boxes stay readable.
  const bool log_y = lo > 0 && hi / lo > 100;
  const Eigen::Vector2d y_range = log_y ? Eigen::Vector2d(std::pow(10.0, std::floor(std::log10(lo))),
                                                          std::pow(10.0, std::ceil(std::log10(hi * 1.0001))))
                                        : NiceRange(std::min(0.0, lo), hi * 1.05);
  const Axes axes = MakeAxes(area, {0.0, static_cast<double>(sw.scenarios.size())}, y_range, log_y);
  const std::vector<double> yt = log_y ? LogTicks(axes.y0, axes.y1) : NiceTicks(axes.y0, axes.y1, 5);
  // Horizontal grid only: x is categorical.
  for (double y : yt) {
    const double py = axes.ToPixel(0, y).y();
    c.Line({area.left, py}, {area.right, py}, {color::kGrid, 1.0, {}});
  }
  const double group_w = (area.right - area.left) / sw.scenarios.size();
  const double box_w = std::min(60.0, 0.8 * group_w / sw.algorithms.size());
  for (size_t s = 0; s < sw.scenarios.size(); ++s) {
    const double gx = area.left + (s + 0.5) * group_w;
    c.Text(gx, area.bottom + 12, sw.scenarios[s], {.size_px = kStyle.label_px, .h = HAlign::kCenter, .v = VAlign::kTop});
    for (size_t a = 0; a < sw.algorithms.size(); ++a) {
      const SampleSummary& g = stats[s][a];
      if (g.n == 0) continue;
      const Rgba col = ModuleColor(sw.baseline, a);
      const double x = gx + (a - 0.5 * (sw.algorithms.size() - 1)) * box_w * 1.15;
      auto Y = [&](double v) { return axes.ToPixel(0, v).y(); };
      const Stroke line{col, 1.6, {}};
      c.Line({x, Y(g.whisker_lo)}, {x, Y(g.q1)}, line);
      c.Line({x, Y(g.q3)}, {x, Y(g.whisker_hi)}, line);
      for (double w : {g.whisker_lo, g.whisker_hi}) c.Line({x - 0.25 * box_w, Y(w)}, {x + 0.25 * box_w, Y(w)}, line);
      c.FillRect(x - 0.5 * box_w, Y(g.q3), x + 0.5 * box_w, Y(g.q1), col.WithAlpha(0.3));
      c.Polyline({{x - 0.5 * box_w, Y(g.q3)}, {x + 0.5 * box_w, Y(g.q3)}, {x + 0.5 * box_w, Y(g.q1)},
                  {x - 0.5 * box_w, Y(g.q1)}, {x - 0.5 * box_w, Y(g.q3)}}, line);
      c.Line({x - 0.5 * box_w, Y(g.median)}, {x + 0.5 * box_w, Y(g.median)}, {col, 3.0, {}});
      for (double o : g.outliers) DrawMarker(c, {x, Y(o)}, MarkerShape::kRing, 8.0, col);
    }
  }
  // Frame and y axis (x tick labels are the scenario names drawn above).
  Axes frame_axes = axes;
  c.Polyline({{area.left, area.top}, {area.right, area.top}, {area.right, area.bottom}, {area.left, area.bottom}, {area.left, area.top}},
             {color::kBlack, 1.2, {}});
  double max_w = 0;
  for (double y : yt) {
    const std::string label = FormatTick(y, log_y ? y : (yt.size() > 1 ? yt[1] - yt[0] : 1.0));
    max_w = std::max(max_w, TextWidth(label, kStyle.tick_px));
    c.Line({area.left - 6, axes.ToPixel(0, y).y()}, {area.left, axes.ToPixel(0, y).y()}, {color::kBlack, 1.2, {}});
    c.Text(area.left - 11, axes.ToPixel(0, y).y(), label, {.size_px = kStyle.tick_px, .h = HAlign::kRight, .v = VAlign::kMiddle});
  }
  c.Text(area.left - 24 - max_w, 0.5 * (area.top + area.bottom), MetricLabel(metric) + (log_y ? " (log scale)" : ""),
         {.size_px = kStyle.label_px, .h = HAlign::kCenter, .v = VAlign::kBottom, .vertical = true});
  c.Text(0.5 * (area.left + area.right), area.bottom + 50, "scenario", {.size_px = kStyle.label_px, .h = HAlign::kCenter, .v = VAlign::kTop});
  c.Text(0.5 * (area.left + area.right), area.top - 14, MetricLabel(metric) + " per module and scenario (all seeds" +
         std::string(sw.results.grid_keys.empty() ? ")" : " and grid cells)"), {.size_px = kStyle.title_px, .h = HAlign::kCenter, .weight = FontWeight::kBold});
  std::vector<LegendEntry> legend;
  for (size_t a = 0; a < sw.algorithms.size(); ++a)
    legend.push_back({.label = sw.algorithms[a], .line = {{}, 0.0, {}}, .patch = ModuleColor(sw.baseline, a).WithAlpha(0.5)});
  DrawLegendAt(c, area.right + 14, area.top, legend);
  SaveFigure(c, stem);
  return true;
}

/// The values a swept key takes, as written in results.csv: sorted by value and placed at
/// that value when all are numbers, else categories at 0, 1, ... in order of appearance.
struct Levels {
  std::vector<std::string> text;
  std::vector<double> x;
  bool numeric = true;
};

Levels LevelsOf(const SweepFolder& sw, const std::string& key) {
  Levels lv;
  for (const auto& r : sw.results.rows) {
    const std::string* v = GridValue(r, key);
    if (v && std::find(lv.text.begin(), lv.text.end(), *v) == lv.text.end()) lv.text.push_back(*v);
  }
  std::vector<std::pair<double, std::string>> numbers;
  for (const auto& t : lv.text) {
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (t.empty() || *end != '\0') lv.numeric = false;
    numbers.push_back({v, t});
  }
  if (lv.numeric) {
    std::sort(numbers.begin(), numbers.end());
    lv.text.clear();
    for (const auto& [v, t] : numbers) {
      lv.text.push_back(t);
      lv.x.push_back(v);
    }
  } else {
    for (size_t i = 0; i < lv.text.size(); ++i) lv.x.push_back(static_cast<double>(i));
  }
  return lv;
}

bool MatchesLevel(const ResultRow& r, const std::string& key, const std::string& level) {
  const std::string* v = GridValue(r, key);
  return v && *v == level;
}

bool VersusFigure(const SweepFolder& sw, const std::string& key, const std::string& metric, const std::string& stem) {
  const Levels lv = LevelsOf(sw, key);
  const std::vector<double>& levels = lv.x;
  if (levels.size() < 2) return false;
  struct Curve { std::string label; Rgba color; std::vector<SampleSummary> at; std::vector<MeanInterval> ci; };
  std::vector<Curve> curves;
  double lo = INFINITY, hi = -INFINITY;
  for (size_t s = 0; s < sw.scenarios.size(); ++s)
    for (size_t a = 0; a < sw.algorithms.size(); ++a) {
      Curve cu{sw.algorithms[a] + (sw.scenarios.size() > 1 ? " / " + sw.scenarios[s] : ""),
               sw.scenarios.size() > 1 ? SeriesColor(static_cast<int>(a + s * sw.algorithms.size())) : ModuleColor(sw.baseline, a), {}};
      for (const std::string& level : lv.text) {
        const std::vector<double> v = Values(sw, metric, [&](const ResultRow& r) {
          return r.scenario == sw.scenarios[s] && r.algorithm == sw.algorithms[a] && MatchesLevel(r, key, level);
        });
        cu.at.push_back(Summarize(v));
        cu.ci.push_back(IntervalOfMean(v, sw.interval, /*nonnegative=*/true));  // the plotted metrics are errors
        const MeanInterval& g = cu.ci.back();
        if (g.n > 0) { lo = std::min(lo, g.lo); hi = std::max(hi, g.hi); }
      }
      curves.push_back(cu);
    }
  if (!(lo <= hi)) return false;
  Canvas c(1100, 660, 3);
  const double pad = lv.numeric ? 0.05 * (levels.back() - levels.front()) : 0.5;
  Axes axes = MakeAxes({112, 62, 1100 - 30, 660 - 88}, {levels.front() - pad, levels.back() + pad},
                             NiceRange(std::min(0.0, lo), hi * 1.05));
  if (!lv.numeric)
    for (size_t i = 0; i < levels.size(); ++i) axes.x_categories.push_back({levels[i], lv.text[i]});
  DrawGrid(c, axes);
  std::vector<LegendEntry> legend;
  std::vector<Eigen::Vector2d> pts;
  for (size_t k = 0; k < curves.size(); ++k) {
    const Curve& cu = curves[k];
    // Dodge overlapping error bars sideways by a few pixels per curve.
    const double dx = (k - 0.5 * (curves.size() - 1)) * 5.0;
    std::vector<Eigen::Vector2d> line;
    for (size_t i = 0; i < levels.size(); ++i) {
      const SampleSummary& g = cu.at[i];
      if (g.n == 0) continue;
      const Eigen::Vector2d m = axes.ToPixel(levels[i], g.mean) + Eigen::Vector2d(dx, 0);
      const Eigen::Vector2d a = axes.ToPixel(levels[i], cu.ci[i].lo) + Eigen::Vector2d(dx, 0);
      const Eigen::Vector2d b = axes.ToPixel(levels[i], cu.ci[i].hi) + Eigen::Vector2d(dx, 0);
      c.Line(a, b, {cu.color, 1.6, {}});
      c.Line(a - Eigen::Vector2d(5, 0), a + Eigen::Vector2d(5, 0), {cu.color, 1.6, {}});
      c.Line(b - Eigen::Vector2d(5, 0), b + Eigen::Vector2d(5, 0), {cu.color, 1.6, {}});
      line.push_back(m);
      pts.insert(pts.end(), {a, m, b});
    }
    c.Polyline(line, {cu.color, 2.2, {}});
    for (const auto& m : line) DrawMarker(c, m, MarkerShape::kCircle, 9.0, cu.color);
    legend.push_back({.label = cu.label, .line = {cu.color, 2.2, {}}, .marker = MarkerShape::kCircle, .marker_color = cu.color});
  }
  const std::string how = sw.interval == IntervalMethod::kStudentT    ? "t"
                          : sw.interval == IntervalMethod::kBootstrap ? "bootstrap"
                                                                      : "bootstrap < 10 seeds, else t";
  DrawFrame(c, axes, {MetricLabel(metric) + " vs " + key + " (mean, 95% interval: " + how + ")", key, MetricLabel(metric)});
  DrawLegend(c, axes, legend, pts);
  SaveFigure(c, stem);
  return true;
}

bool HeatmapFigure(const SweepFolder& sw, const std::string& algo, const std::string& metric, const std::string& stem) {
  if (sw.results.grid_keys.size() < 2) return false;
  const std::string kx = sw.results.grid_keys[0], ky = sw.results.grid_keys[1];
  const Levels lx = LevelsOf(sw, kx), ly = LevelsOf(sw, ky);
  const std::vector<std::string>& xs = lx.text;
  const std::vector<std::string>& ys = ly.text;
  if (xs.size() < 2 || ys.size() < 2) return false;
  std::vector<std::vector<double>> mean(ys.size(), std::vector<double>(xs.size(), NAN));
  double lo = INFINITY, hi = -INFINITY;
  for (size_t j = 0; j < ys.size(); ++j)
    for (size_t i = 0; i < xs.size(); ++i) {
      const SampleSummary g = Summarize(Values(sw, metric, [&](const ResultRow& r) {
        return r.algorithm == algo && MatchesLevel(r, kx, xs[i]) && MatchesLevel(r, ky, ys[j]);
      }));
      if (g.n == 0) continue;
      mean[j][i] = g.mean;
      lo = std::min(lo, g.mean);
      hi = std::max(hi, g.mean);
    }
  if (!(lo <= hi)) return false;
  double y_tick_w = 0.0;  // long category labels widen the left margin
  for (const auto& y : ys) y_tick_w = std::max(y_tick_w, TextWidth(y, kStyle.tick_px));
  const double left = std::max(150.0, y_tick_w + 60.0);
  Canvas c(static_cast<int>(left) + 850, 720, 3);
  const PlotArea area{left, 62, c.width() - 220.0, 720 - 100};
  const double cw = (area.right - area.left) / xs.size(), ch = (area.bottom - area.top) / ys.size();
  auto u = [&](double v) { return hi > lo ? (v - lo) / (hi - lo) : 0.5; };
  char buf[32];
  for (size_t j = 0; j < ys.size(); ++j)
    for (size_t i = 0; i < xs.size(); ++i) {
      const double x0 = area.left + i * cw, y1 = area.bottom - j * ch;
      const double v = mean[j][i];
      const Rgba col = std::isfinite(v) ? Viridis(u(v)) : Rgba{0.85, 0.85, 0.85};
      c.FillRect(x0, y1 - ch, x0 + cw, y1, col);
      std::snprintf(buf, sizeof buf, std::isfinite(v) ? "%.3g" : "n/a", v);
      const double lum = 0.2126 * col.r + 0.7152 * col.g + 0.0722 * col.b;
      c.Text(x0 + 0.5 * cw, y1 - 0.5 * ch, buf, {.size_px = kStyle.legend_px, .color = lum > 0.5 ? color::kBlack : color::kWhite,
                                                .h = HAlign::kCenter, .v = VAlign::kMiddle});
    }
  c.Polyline({{area.left, area.top}, {area.right, area.top}, {area.right, area.bottom}, {area.left, area.bottom}, {area.left, area.top}},
             {color::kBlack, 1.2, {}});
  for (size_t i = 0; i < xs.size(); ++i)
    c.Text(area.left + (i + 0.5) * cw, area.bottom + 10, xs[i],
           {.size_px = kStyle.tick_px, .h = HAlign::kCenter, .v = VAlign::kTop});
  for (size_t j = 0; j < ys.size(); ++j)
    c.Text(area.left - 10, area.bottom - (j + 0.5) * ch, ys[j],
           {.size_px = kStyle.tick_px, .h = HAlign::kRight, .v = VAlign::kMiddle});
  c.Text(0.5 * (area.left + area.right), area.bottom + 46, kx, {.size_px = kStyle.label_px, .h = HAlign::kCenter, .v = VAlign::kTop});
  c.Text(area.left - 20 - y_tick_w, 0.5 * (area.top + area.bottom), ky, {.size_px = kStyle.label_px, .h = HAlign::kCenter, .v = VAlign::kBottom, .vertical = true});
  const std::string title = MetricLabel(metric) + " of " + algo +
                            (sw.scenarios.size() > 1 ? " (mean over seeds and scenarios)" : " (mean over seeds)");
  const double title_w = TextWidth(title, kStyle.title_px, FontWeight::kBold);
  c.Text(0.5 * c.width(), area.top - 14, title,
         {.size_px = std::min(kStyle.title_px, kStyle.title_px * (c.width() - 20.0) / title_w), .h = HAlign::kCenter,
          .weight = FontWeight::kBold});
  // Colour bar with round ticks.
  const double bx0 = area.right + 30, bx1 = bx0 + 24;
  const int steps = 128;
  for (int k = 0; k < steps; ++k) {
    const double y0 = area.bottom - (area.bottom - area.top) * k / steps, y1 = area.bottom - (area.bottom - area.top) * (k + 1) / steps;
    c.FillRect(bx0, y1 - 0.3, bx1, y0 + 0.3, Viridis((k + 0.5) / steps));
  }
  c.Polyline({{bx0, area.top}, {bx1, area.top}, {bx1, area.bottom}, {bx0, area.bottom}, {bx0, area.top}}, {color::kBlack, 1.0, {}});
  const std::vector<double> ticks = NiceTicks(lo, hi > lo ? hi : lo + 1e-9, 5);
  double tick_w = 0.0;
  for (double t : ticks) tick_w = std::max(tick_w, TextWidth(FormatTick(t, ticks.size() > 1 ? ticks[1] - ticks[0] : 1.0), kStyle.tick_px));
  c.Text(bx1 + 18 + tick_w, 0.5 * (area.top + area.bottom), MetricLabel(metric),
         {.size_px = kStyle.label_px, .h = HAlign::kCenter, .v = VAlign::kTop, .vertical = true});
  for (double t : ticks) {
    const double y = area.bottom - (area.bottom - area.top) * u(t);
    c.Line({bx1, y}, {bx1 + 5, y}, {color::kBlack, 1.0, {}});
    c.Text(bx1 + 9, y, FormatTick(t, ticks.size() > 1 ? ticks[1] - ticks[0] : 1.0), {.size_px = kStyle.tick_px, .v = VAlign::kMiddle});
  }
  SaveFigure(c, stem);
  return true;
}

}  // namespace

std::vector<std::string> RenderSweepFiguresListed(const std::string& sweep_dir) {
  const SweepFolder sw = ReadSweepFolder(sweep_dir);
  fs::create_directories(fs::path(sweep_dir) / "figures");
  std::vector<std::string> written;
  auto emit = [&](const std::string& name, bool ok) { if (ok) written.push_back("figures/" + name); };
  auto path = [&](const std::string& name) { return (fs::path(sweep_dir) / "figures" / name).string(); };
  const std::vector<std::string> metrics = PrimaryMetrics(sw);
  for (const auto& m : metrics) emit("box_" + m, BoxFigure(sw, m, path("box_" + m)));
  if (!metrics.empty()) {
    for (const auto& k : sw.results.grid_keys) emit("vs_" + Safe(k), VersusFigure(sw, k, metrics[0], path("vs_" + Safe(k))));
    for (const auto& a : sw.algorithms) emit("heatmap_" + Safe(a), HeatmapFigure(sw, a, metrics[0], path("heatmap_" + Safe(a))));
  }
  return written;
}

void RenderSweepFigures(const std::string& sweep_dir) { RenderSweepFiguresListed(sweep_dir); }

}  // namespace slambox::render
