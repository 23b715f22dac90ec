#pragma once
// Legends and point markers.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "render/axes.hpp"

namespace slambox::render {

enum class MarkerShape { kNone, kCircle, kSquare, kTriangle, kDiamond, kCross, kRing };  ///< kRing: open circle

/// A filled marker of `size_px` (its bounding-box side) with a thin darker outline.
void DrawMarker(Canvas& canvas, const Eigen::Vector2d& center, MarkerShape shape, double size_px, const Rgba& fill);

struct LegendEntry {
  std::string label;
  Stroke line;                 ///< drawn when line.width_px > 0
  MarkerShape marker = MarkerShape::kNone;
  Rgba marker_color = color::kBlack;
  Rgba patch = {0, 0, 0, 0};   ///< a filled swatch when patch.a > 0 (areas, bands)
};

/// Draws the legend inside the plot area in the corner whose box covers the fewest of
/// `data_px` (pixel positions of the plotted data); returns that box (x0, y0, x1, y1).
Eigen::Vector4d DrawLegend(Canvas& canvas, const Axes& axes, const std::vector<LegendEntry>& entries,
                           const std::vector<Eigen::Vector2d>& data_px, const FigureStyle& style = {});
/// Draws the legend with its top-left corner at (x, y) (e.g. outside the plot area).
Eigen::Vector4d DrawLegendAt(Canvas& canvas, double x, double y, const std::vector<LegendEntry>& entries,
                             const FigureStyle& style = {});
/// Width and height [px] the legend needs.
Eigen::Vector2d LegendSize(const std::vector<LegendEntry>& entries, const FigureStyle& style = {});

}  // namespace slambox::render
