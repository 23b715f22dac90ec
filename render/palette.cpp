#include "render/palette.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace slambox::render {

Rgba SeriesColor(int i) {
  static constexpr std::array<Rgba, 6> kSeries{color::kBlue, color::kVermillion, color::kBluishGreen,
                                               color::kReddishPurple, color::kSkyBlue, color::kOrange};
  return kSeries[static_cast<size_t>(((i % 6) + 6) % 6)];
}

Rgba ModuleColor(const std::vector<bool>& is_baseline, size_t i) {
  if (is_baseline.at(i)) return color::kOrange;
  int k = 0;
  for (size_t j = 0; j < i; ++j) k += !is_baseline[j];
  // Five Okabe-Ito hues (orange stays the baselines', black is ground truth), then the same
  // hues darkened, then lightened toward white: up to fifteen modules stay distinct.
  const Rgba base = SeriesColor(k % 5);
  switch ((k / 5) % 3) {
    case 0: return base;
    case 1: return {0.55 * base.r, 0.55 * base.g, 0.55 * base.b, base.a};
    default: return {0.45 + 0.55 * base.r, 0.45 + 0.55 * base.g, 0.45 + 0.55 * base.b, base.a};
  }
}

Rgba Viridis(double u) {
  // Anchors sampled from matplotlib's viridis at u = 0, 1/8, ..., 1.
  static constexpr std::array<Rgba, 9> kAnchors{
      Rgba{0.267, 0.005, 0.329}, Rgba{0.283, 0.141, 0.458}, Rgba{0.254, 0.265, 0.530},
      Rgba{0.207, 0.372, 0.553}, Rgba{0.164, 0.471, 0.558}, Rgba{0.128, 0.567, 0.551},
      Rgba{0.135, 0.659, 0.518}, Rgba{0.478, 0.821, 0.318}, Rgba{0.993, 0.906, 0.144}};
  if (!std::isfinite(u)) u = 0.0;
  const double x = std::clamp(u, 0.0, 1.0) * 8.0;
  const int i = std::min(7, static_cast<int>(x));
  const double f = x - i;
  const Rgba& a = kAnchors[i];
  const Rgba& b = kAnchors[i + 1];
  return {a.r + f * (b.r - a.r), a.g + f * (b.g - a.g), a.b + f * (b.b - a.b), 1.0};
}

std::string HexColor(const Rgba& c) {
  auto byte = [](double v) { return static_cast<int>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); };
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", byte(c.r), byte(c.g), byte(c.b));
  return buf;
}

}  // namespace slambox::render
