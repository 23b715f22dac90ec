#include "render/plot_lines.hpp"

#include <algorithm>
#include <cmath>

namespace slambox::render {

std::vector<std::vector<Eigen::Vector2d>> SeriesPixels(const Axes& axes, const std::vector<double>& x,
                                                       const std::vector<double>& y) {
  std::vector<std::vector<Eigen::Vector2d>> out(1);
  const size_t n = std::min(x.size(), y.size());
  for (size_t i = 0; i < n; ++i) {
    const bool ok = std::isfinite(x[i]) && std::isfinite(y[i]) && (!axes.log_y || y[i] > 0.0);
    if (!ok) {
      if (!out.back().empty()) out.emplace_back();
      continue;
    }
    const Eigen::Vector2d q = axes.ToPixel(x[i], y[i]);
    if (out.back().empty() || (q - out.back().back()).squaredNorm() > 0.04 || i + 1 == n) out.back().push_back(q);
  }
  if (out.back().empty()) out.pop_back();
  return out;
}

Eigen::Vector2d FiniteRange(const std::vector<double>& y, bool positive) {
  double lo = INFINITY, hi = -INFINITY;
  for (double v : y)
    if (std::isfinite(v) && (!positive || v > 0.0)) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  if (lo > hi) return {NAN, NAN};
  return {lo, hi};
}

}  // namespace slambox::render
