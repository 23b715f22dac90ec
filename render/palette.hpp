#pragma once
// Colours for figures. Series colours are the Okabe-Ito palette (Okabe & Ito 2008,
// "Color Universal Design"), distinguishable under the common colour-vision deficiencies;
// sequential data use viridis (van der Walt & Smith 2015), also perceptually uniform and
// colorblind-safe.
#include <string>
#include <vector>

namespace slambox::render {

struct Rgba {
  double r = 0.0, g = 0.0, b = 0.0;  ///< [0, 1]
  double a = 1.0;                    ///< opacity [0, 1]
  Rgba WithAlpha(double alpha) const { return {r, g, b, alpha}; }
  bool operator==(const Rgba&) const = default;
};

namespace color {
inline constexpr Rgba kBlack{0, 0, 0};
inline constexpr Rgba kWhite{1, 1, 1};
inline constexpr Rgba kOrange{0.902, 0.624, 0.0};
inline constexpr Rgba kSkyBlue{0.337, 0.706, 0.914};
inline constexpr Rgba kBluishGreen{0.0, 0.620, 0.451};
inline constexpr Rgba kYellow{0.941, 0.894, 0.259};
inline constexpr Rgba kBlue{0.0, 0.447, 0.698};
inline constexpr Rgba kVermillion{0.835, 0.369, 0.0};
inline constexpr Rgba kReddishPurple{0.800, 0.475, 0.655};
inline constexpr Rgba kGrid{0.88, 0.88, 0.88};
inline constexpr Rgba kWall{0.55, 0.55, 0.55};  ///< lighter than ground truth (black)
inline constexpr Rgba kGroundTruth{0.0, 0.0, 0.0};
}  // namespace color

/// The i-th series colour (Okabe-Ito without black and yellow, which are reserved for
/// ground truth and too light on white; orange last, as the baselines' colour); cycles after 6.
Rgba SeriesColor(int i);
/// Colour of module i of a list, the same in every figure: a baseline module
/// (ModuleInfo::baseline, e.g. odometry) is orange, the others take five SeriesColor hues
/// in order, then the same darkened, then lightened (fifteen distinct colours before any
/// repeats). `is_baseline[j]` says whether module j is one.
Rgba ModuleColor(const std::vector<bool>& is_baseline, size_t i);
/// Viridis colormap at u in [0, 1] (clamped), piecewise linear through 9 anchors.
Rgba Viridis(double u);
/// "#rrggbb" for SVG / HTML.
std::string HexColor(const Rgba& c);

}  // namespace slambox::render
