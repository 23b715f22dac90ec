#include "core/map_image.hpp"

#include <png.h>

#include <cctype>
#include <cstdio>
#include <fstream>
#include <iterator>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace slambox {

namespace {

// Netpbm header tokens: whitespace-separated, '#' starts a comment to the end of the line.
struct PgmCursor {
  const std::string& bytes;
  std::size_t pos = 0;
  bool NextInt(long& value) {
    while (pos < bytes.size()) {
      if (bytes[pos] == '#') {
        while (pos < bytes.size() && bytes[pos] != '\n') ++pos;
      } else if (std::isspace(static_cast<unsigned char>(bytes[pos]))) {
        ++pos;
      } else {
        break;
      }
    }
    if (pos >= bytes.size() || !std::isdigit(static_cast<unsigned char>(bytes[pos]))) return false;
    value = 0;
    while (pos < bytes.size() && std::isdigit(static_cast<unsigned char>(bytes[pos]))) {
      value = value * 10 + (bytes[pos++] - '0');
      if (value > 1'000'000'000) return false;
    }
    return true;
  }
};

MapImage ReadPgm(const std::string& path, const std::string& bytes, std::int64_t max_pixels) {
  const bool binary = bytes[1] == '5';
  PgmCursor c{bytes};
  c.pos = 2;
  long w = 0, h = 0, maxval = 0;
  const std::string fix = "write a PGM image ('P5' or 'P2', width, height, maxval 1..65535, then the pixels)";
  if (!c.NextInt(w) || !c.NextInt(h) || !c.NextInt(maxval))
    throw InputError(path, 0, "malformed PGM header (width, height and maxval expected)", fix);
  if (w <= 0 || h <= 0) throw InputError(path, 0, "PGM image has no pixels", fix);
  if (maxval < 1 || maxval > 65535) throw InputError(path, 0, "PGM maxval " + std::to_string(maxval) + " outside 1..65535", fix);
  if (static_cast<std::int64_t>(w) * h > max_pixels)
    throw InputError(path, 0, "image of " + std::to_string(w) + " x " + std::to_string(h) + " pixels exceeds the limit of " +
                                  std::to_string(max_pixels), "crop the map or coarsen its resolution");
  MapImage img;
  img.width = static_cast<int>(w);
  img.height = static_cast<int>(h);
  const std::size_t n = static_cast<std::size_t>(w) * h;
  img.shade.resize(n);
  if (binary) {
    // Exactly one whitespace byte separates maxval from the raster.
    if (c.pos >= bytes.size() || !std::isspace(static_cast<unsigned char>(bytes[c.pos])))
      throw InputError(path, 0, "malformed PGM header (no whitespace after maxval)", fix);
    ++c.pos;
    const std::size_t bpp = maxval > 255 ? 2 : 1;
    if (bytes.size() - c.pos < n * bpp)
      throw InputError(path, 0, "truncated PGM: " + std::to_string(n * bpp) + " pixel bytes expected, " +
                                    std::to_string(bytes.size() - c.pos) + " found", "re-export the image");
    const auto* p = reinterpret_cast<const unsigned char*>(bytes.data() + c.pos);
    for (std::size_t i = 0; i < n; ++i) {
      const long v = bpp == 2 ? (long(p[2 * i]) << 8) | p[2 * i + 1] : long(p[i]);
      if (v > maxval) throw InputError(path, 0, "PGM pixel value above maxval", fix);
      img.shade[i] = double(v) / double(maxval);
    }
  } else {
    for (std::size_t i = 0; i < n; ++i) {
      long v = 0;
      if (!c.NextInt(v))
        throw InputError(path, 0, "truncated or malformed P2 PGM: pixel " + std::to_string(i) + " of " + std::to_string(n),
                         fix);
      if (v > maxval) throw InputError(path, 0, "PGM pixel value above maxval", fix);
      img.shade[i] = double(v) / double(maxval);
    }
  }
  return img;
}

MapImage ReadPngMap(const std::string& path, const std::string& bytes, std::int64_t max_pixels) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&png, bytes.data(), bytes.size()))
    throw InputError(path, 0, std::string("malformed PNG: ") + png.message, "re-export the image");
  if (static_cast<std::int64_t>(png.width) * png.height > max_pixels) {
    png_image_free(&png);
    throw InputError(path, 0, "image of " + std::to_string(png.width) + " x " + std::to_string(png.height) +
                                  " pixels exceeds the limit of " + std::to_string(max_pixels),
                     "crop the map or coarsen its resolution");
  }
  const bool has_alpha = (png.format & PNG_FORMAT_FLAG_ALPHA) != 0;
  png.format = PNG_FORMAT_RGBA;  // sRGB 8-bit, as GraphicsMagick hands pixels to nav2
  std::vector<png_byte> rgba(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, rgba.data(), 0, nullptr))
    throw InputError(path, 0, std::string("malformed PNG: ") + png.message, "re-export the image");
  MapImage img;
  img.width = static_cast<int>(png.width);
  img.height = static_cast<int>(png.height);
  const std::size_t n = static_cast<std::size_t>(img.width) * img.height;
  img.shade.resize(n);
  if (has_alpha) img.alpha.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const png_byte* p = &rgba[4 * i];
    img.shade[i] = (double(p[0]) + p[1] + p[2]) / (3.0 * 255.0);
    if (has_alpha) img.alpha[i] = p[3] / 255.0;
  }
  return img;
}

}  // namespace

MapImage ReadMapImage(const std::string& path, std::int64_t max_pixels) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot open the map image", "check the `image:` key of the map YAML");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return DecodeMapImage(path, bytes, max_pixels);
}

MapImage DecodeMapImage(const std::string& path, const std::string& bytes, std::int64_t max_pixels) {
  if (bytes.size() >= 2 && bytes[0] == 'P' && (bytes[1] == '5' || bytes[1] == '2')) return ReadPgm(path, bytes, max_pixels);
  if (bytes.size() >= 8 && bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0) return ReadPngMap(path, bytes, max_pixels);
  throw InputError(path, 0, "not a PGM (P5/P2) or PNG image", "save the map as PGM or PNG");
}

void WritePgm(const std::string& path, int width, int height, const std::vector<std::uint8_t>& pixels) {
  WriteFileAtomic(path, [&](std::ostream& out) {
    out << "P5\n" << width << " " << height << "\n255\n";
    out.write(reinterpret_cast<const char*>(pixels.data()), static_cast<std::streamsize>(pixels.size()));
  });
}

}  // namespace slambox
