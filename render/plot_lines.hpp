#pragma once
// Line series on data axes: NaN values break the line instead of being drawn.
#include <vector>

#include "render/axes.hpp"

namespace slambox::render {

/// Pixel polylines of (x[i], y[i]), split at non-finite values (and at y <= 0 on log axes).
std::vector<std::vector<Eigen::Vector2d>> SeriesPixels(const Axes& axes, const std::vector<double>& x,
                                                       const std::vector<double>& y);
/// Smallest and largest finite y (positive only when `positive`); NaNs when there is none.
Eigen::Vector2d FiniteRange(const std::vector<double>& y, bool positive = false);

}  // namespace slambox::render
