// Error plots of a run: ATE and RPE over distance travelled, and NEES over time against
// the chi-square 95% band. Values come from eval's series files; nothing is computed here.
#include <algorithm>
#include <cmath>
#include <functional>

#include "render/figures_run_parts.hpp"
#include "render/plot_lines.hpp"
#include "render/world_layer.hpp"

namespace slambox::render {

namespace {

struct Line {
  SeriesStyle style;
  const std::vector<double>* x;
  const std::vector<double>* y;
};

/// One panel: grid, clipped series, frame; returns the pixel points (for legend placement).
std::vector<Eigen::Vector2d> DrawPanel(Canvas& c, const Axes& axes, const std::vector<Line>& lines,
                                       const AxesLabels& labels, const std::function<void()>& underlay = {}) {
  if (underlay) underlay();
  DrawGrid(c, axes);
  c.SetClip(axes.area.left, axes.area.top, axes.area.right, axes.area.bottom);
  std::vector<Eigen::Vector2d> all;
  for (const auto& l : lines)
    for (const auto& piece : SeriesPixels(axes, *l.x, *l.y)) {
      if (piece.size() == 1) c.FillCircle(piece[0], l.style.stroke.width_px, l.style.stroke.color);
      else c.Polyline(piece, l.style.stroke);
      all.insert(all.end(), piece.begin(), piece.end());
    }
  c.ResetClip();
  DrawFrame(c, axes, labels);
  return all;
}

Eigen::Vector2d RangeOf(const std::vector<Line>& lines, bool use_x) {
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& l : lines) {
    const Eigen::Vector2d r = FiniteRange(use_x ? *l.x : *l.y);
    if (std::isfinite(r[0])) {
      lo = std::min(lo, r[0]);
      hi = std::max(hi, r[1]);
    }
  }
  return {lo, hi};
}

}  // namespace

bool DrawErrorFigure(const RunFolder& run, const std::string& stem) {
  std::vector<Line> ate, rpe;
  for (size_t i = 0; i < run.algorithms.size(); ++i) {
    const auto& a = run.algorithms[i];
    if (!a.series) continue;
    SeriesStyle s = AlgorithmStyle(run, i);
    if (!a.series->ate_m.empty()) ate.push_back({s, &a.series->distance_m, &a.series->ate_m});
    s.stroke.width_px = 1.6;  // RPE is noisier: thin solid lines stay readable
    s.stroke.dash_px.clear();
    if (!a.series->rpe_trans_m.empty()) rpe.push_back({s, &a.series->rpe_distance_m, &a.series->rpe_trans_m});
  }
  if (ate.empty() && rpe.empty()) return false;
  const int width = kFigureWidthPx, panels = (!ate.empty()) + (!rpe.empty());
  const int panel_h = 420, height = 62 + panels * (panel_h + 60) - 60 + 10;
  Canvas c(width, height, 3);
  std::vector<LegendEntry> legend;
  for (const auto& l : ate.empty() ? rpe : ate) legend.push_back({.label = l.style.label, .line = l.style.stroke});
  double top = 62.0;
  auto panel = [&](const std::vector<Line>& lines, const std::string& title, const std::string& ylabel) {
    const Eigen::Vector2d xr = RangeOf(lines, true), yr = RangeOf(lines, false);
    const PlotArea area{112.0, top, width - 30.0, top + panel_h - 90.0};
    const Axes axes = MakeAxes(area, NiceRange(0.0, std::isfinite(xr[1]) ? xr[1] : 1.0),
                               NiceRange(0.0, std::isfinite(yr[1]) ? yr[1] * 1.05 : 1.0));
    const auto pts = DrawPanel(c, axes, lines, {title, "distance travelled [m]", ylabel});
    if (&lines == (ate.empty() ? &rpe : &ate)) DrawLegend(c, axes, legend, pts);
    top += panel_h + 60.0;
  };
  const std::string suffix = RunTitleSuffix(run);
  if (!ate.empty()) panel(ate, "Absolute trajectory error" + suffix, "ATE [m]");
  if (!rpe.empty()) panel(rpe, "Relative pose error per 1 m of travel", "RPE translation [m]");
  SaveFigure(c, stem);
  return true;
}

bool DrawNeesFigure(const RunFolder& run, const std::string& stem) {
  std::vector<Line> lines;
  double band_lo = NAN, band_hi = NAN;
  for (size_t i = 0; i < run.algorithms.size(); ++i) {
    const auto& a = run.algorithms[i];
    if (!a.series || !std::isfinite(FiniteRange(a.series->nees, true)[0])) continue;
    SeriesStyle s = AlgorithmStyle(run, i);
    s.stroke.width_px = 1.6;
    s.stroke.dash_px.clear();
    lines.push_back({s, &a.series->t_s, &a.series->nees});
    if (!std::isfinite(band_lo)) {
      band_lo = a.series->nees_band_lo;
      band_hi = a.series->nees_band_hi;
    }
  }
  if (lines.empty()) return false;
  const bool band = std::isfinite(band_lo) && std::isfinite(band_hi) && band_hi > band_lo && band_lo > 0.0;
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& l : lines) {
    const Eigen::Vector2d r = FiniteRange(*l.y, true);
    lo = std::min(lo, r[0]);
    hi = std::max(hi, r[1]);
  }
  if (band) {
    lo = std::min(lo, band_lo);
    hi = std::max(hi, band_hi);
  }
  // Log axis from the decade below the smallest value to the decade above the largest.
  const double y0 = std::pow(10.0, std::floor(std::log10(lo))), y1 = std::pow(10.0, std::ceil(std::log10(hi * 1.0001)));
  const Eigen::Vector2d xr = RangeOf(lines, true);
  std::vector<LegendEntry> legend;
  const Rgba band_color = color::kSkyBlue.WithAlpha(0.28);
  if (band) {
    char label[96];
    std::snprintf(label, sizeof label, "95%% \u03c7\u00b2 band [%.3g, %.3g]", band_lo, band_hi);
    legend.push_back({.label = label, .line = {{}, 0.0, {}}, .patch = band_color});
  }
  for (const auto& l : lines) legend.push_back({.label = l.style.label, .line = l.style.stroke});
  // Per-step NEES fills the plot area, so the legend goes to its right.
  const double legend_w = LegendSize(legend).x();
  Canvas c(kFigureWidthPx, 600, 3);
  const Axes axes =
      MakeAxes({112.0, 62.0, kFigureWidthPx - 44.0 - legend_w, 600 - 88.0}, NiceRange(0.0, xr[1]), {y0, y1}, true);
  auto shade_band = [&] {
    const Eigen::Vector2d a = axes.ToPixel(axes.x0, band_lo), b = axes.ToPixel(axes.x1, band_hi);
    c.FillRect(a.x(), b.y(), b.x(), a.y(), band_color);
  };
  const std::string suffix = RunTitleSuffix(run);
  DrawPanel(c, axes, lines, {"Pose NEES over time" + suffix, "time [s]", "NEES (log scale)"},
            band ? std::function<void()>(shade_band) : std::function<void()>());
  DrawLegendAt(c, axes.area.right + 14.0, axes.area.top, legend);
  SaveFigure(c, stem);
  return true;
}

}  // namespace slambox::render
