#include "render/text.hpp"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>

namespace slambox::render {

namespace {

#ifndef SLAMBOX_FONT_DIR
#define SLAMBOX_FONT_DIR "/usr/share/fonts/truetype/dejavu"
#endif

/// One FreeType library and the two faces, loaded once; FreeType faces are not thread
/// safe, so every use holds the mutex.
struct Fonts {
  std::mutex mutex;
  FT_Library library = nullptr;
  FT_Face regular = nullptr;
  FT_Face bold = nullptr;

  Fonts() {
    if (FT_Init_FreeType(&library)) throw std::runtime_error("FreeType initialisation failed");
    regular = Load(SLAMBOX_FONT_DIR "/DejaVuSans.ttf");
    bold = Load(SLAMBOX_FONT_DIR "/DejaVuSans-Bold.ttf");
  }
  FT_Face Load(const char* path) {
    FT_Face face = nullptr;
    if (FT_New_Face(library, path, 0, &face))
      throw std::runtime_error(std::string("cannot load font ") + path + " (install fonts-dejavu-core)");
    return face;
  }
};

Fonts& GetFonts() {
  static Fonts fonts;
  return fonts;
}

struct PlacedGlyph {
  int left = 0, top = 0, width = 0, rows = 0;  // pixel box relative to pen origin / baseline
  std::vector<std::uint8_t> bitmap;
};

}  // namespace

std::vector<char32_t> DecodeUtf8(const std::string& text) {
  std::vector<char32_t> out;
  for (size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    int extra = c < 0x80 ? 0 : (c >> 5) == 0x6 ? 1 : (c >> 4) == 0xE ? 2 : (c >> 3) == 0x1E ? 3 : -1;
    if (extra < 0 || i + extra >= text.size()) {
      out.push_back(0xFFFD);
      ++i;
      continue;
    }
    char32_t cp = extra == 0 ? c : c & (0x3F >> extra);
    bool ok = true;
    for (int k = 1; k <= extra; ++k) {
      const auto cc = static_cast<unsigned char>(text[i + k]);
      if ((cc >> 6) != 0x2) ok = false;
      cp = (cp << 6) | (cc & 0x3F);
    }
    out.push_back(ok ? cp : 0xFFFD);
    i += ok ? extra + 1 : 1;
  }
  return out;
}

TextMask RasterizeText(const std::string& text, double size_px, FontWeight weight) {
  Fonts& fonts = GetFonts();
  std::lock_guard<std::mutex> lock(fonts.mutex);
  FT_Face face = weight == FontWeight::kBold ? fonts.bold : fonts.regular;
  FT_Set_Char_Size(face, 0, static_cast<FT_F26Dot6>(std::lround(size_px * 64.0)), 72, 72);

  // Pen positions in 26.6 fixed point: kerning between pairs, advances unhinted.
  std::vector<PlacedGlyph> glyphs;
  long pen_26_6 = 0;
  FT_UInt previous = 0;
  for (char32_t cp : DecodeUtf8(text)) {
    const FT_UInt index = FT_Get_Char_Index(face, cp);
    if (previous && index && FT_HAS_KERNING(face)) {
      FT_Vector kern;
      FT_Get_Kerning(face, previous, index, FT_KERNING_UNFITTED, &kern);
      pen_26_6 += kern.x;
    }
    if (FT_Load_Glyph(face, index, FT_LOAD_NO_HINTING) || FT_Render_Glyph(face->glyph, FT_RENDER_MODE_NORMAL)) continue;
    const FT_GlyphSlot slot = face->glyph;
    PlacedGlyph g;
    g.left = static_cast<int>(std::lround(pen_26_6 / 64.0)) + slot->bitmap_left;
    g.top = slot->bitmap_top;
    g.width = static_cast<int>(slot->bitmap.width);
    g.rows = static_cast<int>(slot->bitmap.rows);
    for (int r = 0; r < g.rows; ++r) {
      const unsigned char* row = slot->bitmap.buffer + r * slot->bitmap.pitch;
      g.bitmap.insert(g.bitmap.end(), row, row + g.width);
    }
    glyphs.push_back(std::move(g));
    pen_26_6 += slot->advance.x;
    previous = index;
  }

  TextMask mask;
  mask.advance_px = pen_26_6 / 64.0;
  int x0 = 0, x1 = 1, ascent = 1, descent = 0;
  for (const auto& g : glyphs) {
    if (g.width == 0 || g.rows == 0) continue;
    x0 = std::min(x0, g.left);
    x1 = std::max(x1, g.left + g.width);
    ascent = std::max(ascent, g.top);
    descent = std::max(descent, g.rows - g.top);
  }
  x1 = std::max(x1, static_cast<int>(std::ceil(mask.advance_px)));
  mask.origin_x = -x0;
  mask.baseline_y = ascent;
  mask.width = x1 - x0;
  mask.height = ascent + descent;
  mask.coverage.assign(static_cast<size_t>(mask.width) * mask.height, 0);
  for (const auto& g : glyphs)
    for (int r = 0; r < g.rows; ++r)
      for (int c = 0; c < g.width; ++c) {
        const int x = g.left - x0 + c, y = ascent - g.top + r;
        if (x < 0 || y < 0 || x >= mask.width || y >= mask.height) continue;
        auto& dst = mask.coverage[static_cast<size_t>(y) * mask.width + x];
        dst = std::max(dst, g.bitmap[static_cast<size_t>(r) * g.width + c]);
      }
  return mask;
}

double TextWidth(const std::string& text, double size_px, FontWeight weight) {
  return RasterizeText(text, size_px, weight).advance_px;
}

}  // namespace slambox::render
