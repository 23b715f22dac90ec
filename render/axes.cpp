#include "render/axes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace slambox::render {

Eigen::Vector2d Axes::ToPixel(double x, double y) const {
  const double u = (x - x0) / (x1 - x0);
  const double v = log_y ? (std::log10(y) - std::log10(y0)) / (std::log10(y1) - std::log10(y0)) : (y - y0) / (y1 - y0);
  return {area.left + u * (area.right - area.left), area.bottom - v * (area.bottom - area.top)};
}

double NiceStep(double span, int target_count) {
  if (!(span > 0.0) || !std::isfinite(span)) return 1.0;
  const double raw = span / std::max(1, target_count);
  const double decade = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / decade;
  const double m = f < 1.5 ? 1.0 : f < 3.5 ? 2.0 : f < 7.5 ? 5.0 : 10.0;
  return m * decade;
}

std::vector<double> NiceTicks(double lo, double hi, int target_count) {
  std::vector<double> ticks;
  const double step = NiceStep(hi - lo, target_count);
  const double eps = 1e-9 * step;
  for (long k = static_cast<long>(std::ceil((lo - eps) / step)); k * step <= hi + eps; ++k) {
    const double v = k * step;
    ticks.push_back(std::abs(v) < eps ? 0.0 : v);  // no "-0"
  }
  return ticks;
}

std::vector<double> LogTicks(double lo, double hi) {
  std::vector<double> ticks;
  const int d0 = static_cast<int>(std::floor(std::log10(lo) + 1e-9)), d1 = static_cast<int>(std::ceil(std::log10(hi) - 1e-9));
  const bool fine = std::log10(hi / lo) < 3.0;  // fewer than 3 decades shown
  for (int d = d0; d <= d1; ++d)
    for (double m : fine ? std::vector<double>{1, 2, 5} : std::vector<double>{1}) {
      const double v = m * std::pow(10.0, d);
      if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9)) ticks.push_back(v);
    }
  return ticks;
}

std::string FormatTick(double value, double step) {
  const int decimals = std::max(0, static_cast<int>(std::ceil(-std::log10(step) - 1e-9)));
  if (std::abs(value) < 1e-9 * step) value = 0.0;
  char buf[64];
  if (std::abs(value) >= 1e6 || (value != 0.0 && std::abs(value) < 1e-4)) std::snprintf(buf, sizeof buf, "%.0e", value);
  else std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
  std::string s = buf;
  if (s.rfind("-0", 0) == 0 && std::stod(s) == 0.0) s = s.substr(1);
  if (!s.empty() && s[0] == '-') s = "\u2212" + s.substr(1);  // a typographic minus sign
  return s;
}

Eigen::Vector2d NiceRange(double lo, double hi, double pad, int target_count) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) return {0.0, 1.0};
  if (hi - lo < 1e-12) {
    const double half = std::max(0.5, 0.1 * std::abs(lo));
    lo -= half;
    hi += half;
  }
  const double span = hi - lo;
  lo -= pad * span;
  hi += pad * span;
  const double step = NiceStep(hi - lo, target_count);
  return {std::floor(lo / step + 1e-9) * step, std::ceil(hi / step - 1e-9) * step};
}

Axes MakeAxes(const PlotArea& area, Eigen::Vector2d x_range, Eigen::Vector2d y_range, bool log_y) {
  Axes a;
  a.area = area;
  a.x0 = x_range[0];
  a.x1 = x_range[1] > x_range[0] ? x_range[1] : x_range[0] + 1.0;
  a.y0 = y_range[0];
  a.y1 = y_range[1] > y_range[0] ? y_range[1] : y_range[0] + 1.0;
  a.log_y = log_y;
  return a;
}

Axes MakeEqualAspectAxes(const PlotArea& area, const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) {
  const double w_px = area.right - area.left, h_px = area.bottom - area.top;
  const Eigen::Vector2d span = (hi - lo).cwiseMax(Eigen::Vector2d(1e-6, 1e-6));
  const double m_per_px = std::max(span.x() / w_px, span.y() / h_px);
  const Eigen::Vector2d center = 0.5 * (lo + hi);
  const Eigen::Vector2d half(0.5 * w_px * m_per_px, 0.5 * h_px * m_per_px);
  return MakeAxes(area, {center.x() - half.x(), center.x() + half.x()}, {center.y() - half.y(), center.y() + half.y()});
}

namespace {
std::vector<double> YTicks(const Axes& a) {
  return a.log_y ? LogTicks(a.y0, a.y1) : NiceTicks(a.y0, a.y1, std::max(3, static_cast<int>((a.area.bottom - a.area.top) / 90)));
}
std::vector<double> XTicks(const Axes& a) {
  if (!a.x_categories.empty()) {
    std::vector<double> t;
    for (const auto& [x, label] : a.x_categories) t.push_back(x);
    return t;
  }
  return NiceTicks(a.x0, a.x1, std::max(3, static_cast<int>((a.area.right - a.area.left) / 110)));
}
}  // namespace

void DrawGrid(Canvas& c, const Axes& a, const FigureStyle& st) {
  const Stroke grid{color::kGrid, st.grid_width_px, {}};
  for (double x : XTicks(a)) {
    const double px = a.ToPixel(x, a.log_y ? a.y0 : 0.0).x();
    c.Line({px, a.area.top}, {px, a.area.bottom}, grid);
  }
  for (double y : YTicks(a)) {
    const double py = a.ToPixel(a.x0, y).y();
    c.Line({a.area.left, py}, {a.area.right, py}, grid);
  }
}

void DrawFrame(Canvas& c, const Axes& a, const AxesLabels& labels, const FigureStyle& st) {
  const Stroke frame{color::kBlack, st.frame_width_px, {}};
  const PlotArea& r = a.area;
  c.Polyline({{r.left, r.top}, {r.right, r.top}, {r.right, r.bottom}, {r.left, r.bottom}, {r.left, r.top}}, frame);
  const double tick_len = 6.0;
  TextStyle tick_text{.size_px = st.tick_px, .color = color::kBlack, .h = HAlign::kCenter, .v = VAlign::kTop};
  const std::vector<double> xt = XTicks(a);
  const double xstep = xt.size() > 1 ? xt[1] - xt[0] : 1.0;
  for (double x : xt) {
    const double px = a.ToPixel(x, a.log_y ? a.y0 : 0.0).x();
    c.Line({px, r.bottom}, {px, r.bottom + tick_len}, frame);
    std::string label = FormatTick(x, xstep);
    for (const auto& [cx, text] : a.x_categories)
      if (cx == x) label = text;
    c.Text(px, r.bottom + tick_len + 5, label, tick_text);
  }
  tick_text.h = HAlign::kRight;
  tick_text.v = VAlign::kMiddle;
  const std::vector<double> yt = YTicks(a);
  double max_label_w = 0.0;
  for (double y : yt) {
    const double py = a.ToPixel(a.x0, y).y();
    const double step = a.log_y ? std::pow(10.0, std::floor(std::log10(y) + 1e-9)) : (yt.size() > 1 ? yt[1] - yt[0] : 1.0);
    const std::string label = FormatTick(y, step);
    max_label_w = std::max(max_label_w, TextWidth(label, st.tick_px));
    c.Line({r.left - tick_len, py}, {r.left, py}, frame);
    c.Text(r.left - tick_len - 5, py, label, tick_text);
  }
  const TextStyle label_text{.size_px = st.label_px, .h = HAlign::kCenter, .v = VAlign::kTop};
  if (!labels.x_label.empty())
    c.Text(0.5 * (r.left + r.right), r.bottom + tick_len + 5 + st.tick_px * 1.45, labels.x_label, label_text);
  if (!labels.y_label.empty()) {
    TextStyle v = label_text;
    v.vertical = true;
    v.v = VAlign::kBottom;
    c.Text(r.left - tick_len - 12 - max_label_w, 0.5 * (r.top + r.bottom), labels.y_label, v);
  }
  if (!labels.title.empty()) {
    // Shrink a long title to fit the canvas rather than clip it.
    const double w = TextWidth(labels.title, st.title_px, FontWeight::kBold), room = c.width() - 20.0;
    const double size = w > room ? st.title_px * room / w : st.title_px;
    const double cx = std::clamp(0.5 * (r.left + r.right), 10.0 + 0.5 * std::min(w, room), c.width() - 10.0 - 0.5 * std::min(w, room));
    c.Text(cx, r.top - 14, labels.title, {.size_px = size, .h = HAlign::kCenter, .v = VAlign::kBaseline, .weight = FontWeight::kBold});
  }
}

void DrawScaleBar(Canvas& c, const Axes& a, double x, double y, double max_len_px, const FigureStyle& st) {
  const double px_per_m = a.PixelsPerUnitX();
  double len_m = NiceStep(0.2 * (a.x1 - a.x0), 1);
  while (len_m * px_per_m > max_len_px && len_m > 1e-9) len_m = NiceStep(0.6 * len_m, 1);
  const double len_px = len_m * px_per_m;
  const Stroke bar{color::kBlack, 3.0, {}};
  c.Line({x, y}, {x + len_px, y}, bar);
  c.Line({x, y - 5}, {x, y + 5}, {color::kBlack, 2.0, {}});
  c.Line({x + len_px, y - 5}, {x + len_px, y + 5}, {color::kBlack, 2.0, {}});
  c.Text(x + 0.5 * len_px, y - 9, "scale: " + FormatTick(len_m, len_m) + " m",
         {.size_px = st.legend_px, .h = HAlign::kCenter, .v = VAlign::kBaseline});
}

}  // namespace slambox::render
