#include "render/legend.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace slambox::render {

namespace {
constexpr double kSwatchW = 34.0, kPad = 10.0, kGap = 8.0;

Rgba Darker(const Rgba& c) { return {0.6 * c.r, 0.6 * c.g, 0.6 * c.b, c.a}; }

std::vector<Eigen::Vector2d> ShapePoints(const Eigen::Vector2d& c, MarkerShape shape, double h) {
  switch (shape) {
    case MarkerShape::kSquare: return {c + Eigen::Vector2d(-h, -h), c + Eigen::Vector2d(h, -h), c + Eigen::Vector2d(h, h), c + Eigen::Vector2d(-h, h)};
    case MarkerShape::kTriangle: return {c + Eigen::Vector2d(0, -h * 1.15), c + Eigen::Vector2d(h, h * 0.85), c + Eigen::Vector2d(-h, h * 0.85)};
    case MarkerShape::kDiamond: return {c + Eigen::Vector2d(0, -h * 1.2), c + Eigen::Vector2d(h, 0), c + Eigen::Vector2d(0, h * 1.2), c + Eigen::Vector2d(-h, 0)};
    default: return {};
  }
}
}  // namespace

void DrawMarker(Canvas& canvas, const Eigen::Vector2d& c, MarkerShape shape, double size_px, const Rgba& fill) {
  const double h = 0.5 * size_px;
  const Stroke outline{Darker(fill), std::max(1.0, 0.12 * size_px), {}};
  switch (shape) {
    case MarkerShape::kNone: return;
    case MarkerShape::kCircle: {
      canvas.FillCircle(c, h, fill);
      auto ring = canvas.CirclePoints(c, h);
      ring.push_back(ring.front());
      canvas.Polyline(ring, outline);
      return;
    }
    case MarkerShape::kRing: {
      auto ring = canvas.CirclePoints(c, h);
      ring.push_back(ring.front());
      canvas.Polyline(ring, {fill, std::max(1.5, 0.16 * size_px), {}});
      return;
    }
    case MarkerShape::kCross: {
      const Stroke s{fill, std::max(1.5, 0.22 * size_px), {}};
      canvas.Line(c + Eigen::Vector2d(-h, -h), c + Eigen::Vector2d(h, h), s);
      canvas.Line(c + Eigen::Vector2d(-h, h), c + Eigen::Vector2d(h, -h), s);
      return;
    }
    default: {
      auto pts = ShapePoints(c, shape, h);
      canvas.FillPolygon(pts, fill);
      pts.push_back(pts.front());
      canvas.Polyline(pts, outline);
    }
  }
}

Eigen::Vector2d LegendSize(const std::vector<LegendEntry>& entries, const FigureStyle& st) {
  double w = 0.0;
  for (const auto& e : entries) w = std::max(w, TextWidth(e.label, st.legend_px));
  const double row = st.legend_px * 1.55;
  return {kPad + kSwatchW + kGap + w + kPad, 2 * kPad + row * entries.size() - (row - st.legend_px * 1.2)};
}

Eigen::Vector4d DrawLegendAt(Canvas& canvas, double x, double y, const std::vector<LegendEntry>& entries,
                             const FigureStyle& st) {
  const Eigen::Vector2d size = LegendSize(entries, st);
  canvas.FillRect(x, y, x + size.x(), y + size.y(), color::kWhite.WithAlpha(0.9));
  canvas.Polyline({{x, y}, {x + size.x(), y}, {x + size.x(), y + size.y()}, {x, y + size.y()}, {x, y}},
                  {Rgba{0.6, 0.6, 0.6}, 1.0, {}});
  const double row = st.legend_px * 1.55;
  for (size_t i = 0; i < entries.size(); ++i) {
    const LegendEntry& e = entries[i];
    const double cy = y + kPad + st.legend_px * 0.6 + row * i;
    const double sx0 = x + kPad, sx1 = sx0 + kSwatchW;
    if (e.patch.a > 0) canvas.FillRect(sx0, cy - 0.45 * st.legend_px, sx1, cy + 0.45 * st.legend_px, e.patch);
    if (e.line.width_px > 0) {
      Stroke s = e.line;
      if (!s.dash_px.empty()) s.dash_px = {7, 4};  // short enough to show within the swatch
      canvas.Line({sx0 + 2, cy}, {sx1 - 2, cy}, s);
    }
    DrawMarker(canvas, {0.5 * (sx0 + sx1), cy}, e.marker, 0.75 * st.legend_px, e.marker_color);
    canvas.Text(sx1 + kGap, cy, e.label, {.size_px = st.legend_px, .v = VAlign::kMiddle});
  }
  return {x, y, x + size.x(), y + size.y()};
}

Eigen::Vector4d DrawLegend(Canvas& canvas, const Axes& axes, const std::vector<LegendEntry>& entries,
                           const std::vector<Eigen::Vector2d>& data_px, const FigureStyle& st) {
  if (entries.empty()) return Eigen::Vector4d::Zero();
  const Eigen::Vector2d size = LegendSize(entries, st);
  const PlotArea& r = axes.area;
  const double m = 10.0;
  // Candidates: top-right, top-left, bottom-right, bottom-left (ties keep this order).
  const std::vector<Eigen::Vector2d> corners{{r.right - m - size.x(), r.top + m}, {r.left + m, r.top + m},
                                             {r.right - m - size.x(), r.bottom - m - size.y()},
                                             {r.left + m, r.bottom - m - size.y()}};
  size_t best = 0;
  long best_count = std::numeric_limits<long>::max();
  for (size_t k = 0; k < corners.size(); ++k) {
    long count = 0;
    for (const auto& p : data_px)
      count += p.x() >= corners[k].x() - 4 && p.x() <= corners[k].x() + size.x() + 4 && p.y() >= corners[k].y() - 4 &&
               p.y() <= corners[k].y() + size.y() + 4;
    if (count < best_count) {
      best_count = count;
      best = k;
    }
  }
  return DrawLegendAt(canvas, corners[best].x(), corners[best].y(), entries, st);
}

}  // namespace slambox::render
