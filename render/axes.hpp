#pragma once
// Plot axes: data-to-pixel mapping (linear, log-y, or equal-aspect for world maps), tick
// positions at round numbers (1, 2, 5 x 10^k), the frame, grid, tick labels, axis labels
// with units, the title and a scale bar.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "render/canvas.hpp"

namespace slambox::render {

/// Font sizes and strokes shared by every figure [px].
struct FigureStyle {
  // Sized for a 1000-1200 px wide figure shrunk to one column of a paper (~8 pt text).
  double title_px = 24.0;
  double label_px = 21.0;
  double tick_px = 19.0;
  double legend_px = 19.0;
  double frame_width_px = 1.4;
  double grid_width_px = 1.0;
};

struct PlotArea {
  double left = 0, top = 0, right = 0, bottom = 0;  ///< [px]
};

struct Axes {
  PlotArea area;
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;  ///< data range shown (y0 at the bottom)
  bool log_y = false;                     ///< y on a log10 scale (y0, y1 > 0)
  /// Categorical x: ticks at these positions with these labels instead of round numbers.
  std::vector<std::pair<double, std::string>> x_categories;
  Eigen::Vector2d ToPixel(double x, double y) const;
  Eigen::Vector2d ToPixel(const Eigen::Vector2d& p) const { return ToPixel(p.x(), p.y()); }
  double PixelsPerUnitX() const { return (area.right - area.left) / (x1 - x0); }
};

/// The tick step 1, 2 or 5 x 10^k that gives about `target_count` intervals over `span`.
double NiceStep(double span, int target_count);
/// Multiples of NiceStep within [lo, hi] (ends included up to rounding).
std::vector<double> NiceTicks(double lo, double hi, int target_count = 6);
/// For log axes: decades in [lo, hi], with 2 and 5 between them when fewer than 3 decades.
std::vector<double> LogTicks(double lo, double hi);
/// Tick label with as many decimals as `step` needs ("0.25" for step 0.05 -> "0.25").
std::string FormatTick(double value, double step);

/// [lo, hi] widened by `pad` of the span and out to the nearest ticks (degenerate ranges
/// get a unit span).
Eigen::Vector2d NiceRange(double lo, double hi, double pad = 0.0, int target_count = 6);

/// Linear axes over the data ranges.
Axes MakeAxes(const PlotArea& area, Eigen::Vector2d x_range, Eigen::Vector2d y_range, bool log_y = false);
/// Equal-aspect axes (1 m is the same length in x and y) that contain [lo, hi], centred.
Axes MakeEqualAspectAxes(const PlotArea& area, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi);

struct AxesLabels {
  std::string title;
  std::string x_label;  ///< with unit, e.g. "distance travelled [m]"
  std::string y_label;
};

/// Background grid under the data (call before drawing data).
void DrawGrid(Canvas& canvas, const Axes& axes, const FigureStyle& style = {});
/// Frame, ticks, tick labels, axis labels and title (call after drawing data).
void DrawFrame(Canvas& canvas, const Axes& axes, const AxesLabels& labels, const FigureStyle& style = {});
/// A scale bar of round length (about 1/5 of the plot width, at most `max_len_px`) with
/// its left end at (x, y) [px], e.g. outside the plot under the legend.
void DrawScaleBar(Canvas& canvas, const Axes& axes, double x, double y, double max_len_px, const FigureStyle& style = {});

}  // namespace slambox::render
