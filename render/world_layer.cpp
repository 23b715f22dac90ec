#include "render/world_layer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace slambox::render {

namespace {
constexpr Rgba kPostColor{0.35, 0.35, 0.35};
constexpr Rgba kMoverColor{0.800, 0.475, 0.655, 0.8};
}  // namespace

SeriesStyle AlgorithmStyle(const RunFolder& run, size_t index) {
  std::vector<bool> baseline;
  for (const auto& a : run.algorithms) baseline.push_back(a.baseline);
  const std::string& name = run.algorithms.at(index).name;
  if (baseline[index]) return {name, {ModuleColor(baseline, index), 2.2, {10, 6}}};  // a baseline: dashed
  return {name, {ModuleColor(baseline, index), 2.6, {}}};
}

// Thin and drawn last: the reference stays visible, estimates show as colour on either side.
SeriesStyle GroundTruthStyle() { return {"ground truth", {color::kGroundTruth, 1.8, {}}}; }

WorldFigure::WorldFigure(int width_px, int height_px, Eigen::Vector2d lo, Eigen::Vector2d hi,
                         const std::vector<LegendEntry>& legend, const FigureStyle& style, int supersample)
    : canvas(width_px, height_px, supersample) {
  const double legend_w = legend.empty() ? 140.0 : std::max(140.0, LegendSize(legend, style).x() + 24.0);
  const PlotArea area{108.0, 62.0, width_px - 24.0 - legend_w, height_px - 88.0};
  const Eigen::Vector2d pad = 0.04 * (hi - lo).cwiseMax(Eigen::Vector2d(1.0, 1.0));
  axes = MakeEqualAspectAxes(area, lo - pad, hi + pad);
  DrawGrid(canvas, axes, style);
  canvas.SetClip(area.left, area.top, area.right, area.bottom);
}

void WorldFigure::Finish(const std::string& title, const std::vector<LegendEntry>& legend, const FigureStyle& style) {
  canvas.ResetClip();
  DrawFrame(canvas, axes, {title, "x [m]", "y [m]"}, style);
  // Legend and scale bar outside the plot, on the right, so they never hide data.
  const double x = axes.area.right + 16.0;
  const Eigen::Vector4d box = legend.empty() ? Eigen::Vector4d(x, axes.area.top, canvas.width() - 24.0, axes.area.top)
                                             : DrawLegendAt(canvas, x, axes.area.top, legend, style);
  const double room = std::max(60.0, box[2] - box[0] - 20.0);
  DrawScaleBar(canvas, axes, x + 10.0, box[3] + 24.0 + style.legend_px, room, style);
}

int WorldFigureHeight(int width_px, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                      const std::vector<LegendEntry>& legend, const FigureStyle& style) {
  const double legend_w = legend.empty() ? 140.0 : std::max(140.0, LegendSize(legend, style).x() + 24.0);
  const double plot_w = width_px - 132.0 - legend_w;
  const Eigen::Vector2d span = (hi - lo).cwiseMax(Eigen::Vector2d(1e-3, 1e-3)) * 1.08;
  const double legend_h = (legend.empty() ? 0.0 : LegendSize(legend, style).y()) + 70.0 + 150.0;  // + scale bar
  const double h = std::max(plot_w * span.y() / span.x() + 150.0, legend_h);
  return std::clamp(static_cast<int>(std::lround(h)), 480, 1100);
}

std::pair<Eigen::Vector2d, Eigen::Vector2d> RunExtent(const RunFolder& run, int only_algo) {
  const double inf = std::numeric_limits<double>::infinity();
  Eigen::Vector2d lo(inf, inf), hi(-inf, -inf);
  if (run.has_world) {
    const Bounds b = WorldBounds(run.world);
    if (b.max.x() > b.min.x() || b.max.y() > b.min.y()) {
      lo = b.min;
      hi = b.max;
    }
  }
  for (const auto& p : run.groundtruth) {
    lo = lo.cwiseMin(p.pose.translation());
    hi = hi.cwiseMax(p.pose.translation());
  }
  if (!(lo.x() <= hi.x())) {  // no world, no ground truth (a real log): the estimates and their maps
    const auto add = [&](const Eigen::Vector2d& p) {
      if (!p.allFinite()) return;
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    };
    for (size_t i = 0; i < run.algorithms.size(); ++i) {
      if (only_algo >= 0 && static_cast<int>(i) != only_algo) continue;
      const AlgorithmResult& a = run.algorithms[i];
      for (const auto& p : a.trajectory) add(p.pose.translation());
      if (!a.estimate) continue;
      for (const auto& p : a.estimate->map_points) add(p);  // walls lie beyond the path
      if (const auto& g = a.estimate->grid)
        for (int iy = 0; iy < g->height; ++iy)
          for (int ix = 0; ix < g->width; ++ix)
            if (g->cells[static_cast<size_t>(iy) * g->width + ix] > 50)
              add(g->origin_m + Eigen::Vector2d((ix + 0.5) * g->resolution_m, (iy + 0.5) * g->resolution_m));
    }
    if (!(lo.x() <= hi.x())) return {Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1)};
    return {lo, hi};
  }
  const Eigen::Vector2d margin = 0.5 * (hi - lo).cwiseMax(Eigen::Vector2d(2.0, 2.0));
  const Eigen::Vector2d cap_lo = lo - margin, cap_hi = hi + margin;
  for (size_t i = 0; i < run.algorithms.size(); ++i)
    for (const auto& p : run.algorithms[i].trajectory) {
      if (only_algo >= 0 && static_cast<int>(i) != only_algo) break;
      if (!p.pose.translation().allFinite()) continue;
      lo = lo.cwiseMin(p.pose.translation().cwiseMax(cap_lo));
      hi = hi.cwiseMax(p.pose.translation().cwiseMin(cap_hi));
    }
  return {lo, hi};
}

void DrawWorld(Canvas& c, const Axes& axes, const World& world, bool faint) {
  const Rgba wall = faint ? Rgba{0.75, 0.75, 0.75} : color::kWall;
  const double px_per_m = axes.PixelsPerUnitX();
  for (const auto& m : world.movers) {
    std::vector<Eigen::Vector2d> px;
    for (const auto& p : m.path) px.push_back(axes.ToPixel(p));
    const double w = std::clamp(2.0 * std::max(m.radius_m, 0.5 * m.box_size_m.maxCoeff()) * px_per_m, 2.0, 14.0);
    c.Polyline(px, {faint ? kMoverColor.WithAlpha(0.25) : kMoverColor.WithAlpha(0.35), w, {}});
  }
  for (const auto& s : world.wall_segments) c.Line(axes.ToPixel(s.a), axes.ToPixel(s.b), {wall, faint ? 1.5 : 2.2, {}});
  for (const auto& ci : world.wall_circles) c.FillCircle(axes.ToPixel(ci.center), std::max(1.5, ci.radius_m * px_per_m), wall);
  if (faint) return;
  for (const auto& l : world.landmarks) {
    const double r = std::max(3.5, l.radius_m * px_per_m);
    c.FillCircle(axes.ToPixel(l.position), r, kPostColor);
  }
}

std::vector<LegendEntry> WorldLegend(const World& world) {
  std::vector<LegendEntry> out;
  if (!world.wall_segments.empty() || !world.wall_circles.empty())
    out.push_back({.label = "walls", .line = {color::kWall, 2.2, {}}});
  if (!world.landmarks.empty())
    out.push_back({.label = "posts (true)", .line = {{}, 0.0, {}}, .marker = MarkerShape::kCircle, .marker_color = kPostColor});
  if (!world.movers.empty()) out.push_back({.label = "movers' paths", .line = {kMoverColor.WithAlpha(0.35), 8.0, {}}});
  return out;
}

std::vector<Eigen::Vector2d> PathPixels(const Axes& axes, const std::vector<StampedPose>& poses) {
  std::vector<Eigen::Vector2d> px;
  px.reserve(poses.size());
  for (const auto& p : poses) {
    if (!p.pose.translation().allFinite()) continue;
    const Eigen::Vector2d q = axes.ToPixel(p.pose.translation());
    // Drop points closer than 0.3 px to the previous one: invisible, and keeps SVGs small.
    if (px.empty() || (q - px.back()).squaredNorm() > 0.09) px.push_back(q);
  }
  if (!poses.empty() && px.size() >= 1) {
    const Eigen::Vector2d last = axes.ToPixel(poses.back().pose.translation());
    if (last.allFinite() && (last - px.back()).squaredNorm() > 0.0) px.push_back(last);
  }
  return px;
}

std::vector<StampedPose> PosesOf(const Estimate& estimate) {
  std::vector<StampedPose> out;
  for (const auto& p : estimate.trajectory) out.push_back({p.t_s, p.pose});
  return out;
}

}  // namespace slambox::render
