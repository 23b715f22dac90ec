#pragma once
// Text as real glyphs: FreeType rasterizes DejaVu Sans (antialiased coverage masks).
#include <cstdint>
#include <string>
#include <vector>

namespace slambox::render {

enum class FontWeight { kRegular, kBold };

/// A horizontal line of text rasterized as an 8-bit coverage mask. The pen starts at
/// x = origin_x and the baseline is row baseline_y of the mask.
struct TextMask {
  int width = 0;
  int height = 0;
  int origin_x = 0;    ///< mask column of the pen's start
  int baseline_y = 0;  ///< mask row of the baseline
  double advance_px = 0.0;  ///< pen advance (the text's layout width)
  std::vector<std::uint8_t> coverage;  ///< row-major, 0 = empty, 255 = fully covered
};

/// Rasterizes UTF-8 `text` at `size_px` (the em size in pixels) with kerning.
/// Throws std::runtime_error naming the font file when FreeType cannot load it.
TextMask RasterizeText(const std::string& text, double size_px, FontWeight weight = FontWeight::kRegular);

/// Layout width of `text` in pixels (same as RasterizeText(...).advance_px).
double TextWidth(const std::string& text, double size_px, FontWeight weight = FontWeight::kRegular);

/// Height of a capital letter / digit above the baseline, as a fraction of the em size
/// (DejaVu Sans: 0.729); used to centre text vertically.
inline constexpr double kCapHeightEm = 0.729;

/// UTF-8 decoding (invalid bytes become U+FFFD).
std::vector<char32_t> DecodeUtf8(const std::string& text);

}  // namespace slambox::render
