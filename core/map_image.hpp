#pragma once
// Grey-level images as occupancy maps store them: PGM (P5 binary or P2 text, maxval up
// to 65535) and PNG (any colour type, through libpng's simplified API). Read as shades
// in [0, 1] the way nav2's map_io sees pixels.
#include <cstdint>
#include <string>
#include <vector>

namespace slambox {

struct MapImage {
  int width = 0;
  int height = 0;
  std::vector<double> shade;  ///< row-major from the top row: mean of the colour channels / max, in [0, 1]
  std::vector<double> alpha;  ///< same layout, 1 = opaque; empty when the image has no alpha channel
};

/// Picks PGM or PNG by the file's first bytes. Throws InputError naming the file (and the
/// problem: unknown format, bad header, truncated data, more than `max_pixels`).
MapImage ReadMapImage(const std::string& path, std::int64_t max_pixels = 400'000'000);
/// The same for an image's bytes (`path` names it in messages).
MapImage DecodeMapImage(const std::string& path, const std::string& bytes, std::int64_t max_pixels = 400'000'000);

/// Writes an 8-bit binary PGM (P5) atomically; `pixels` row-major from the top row.
void WritePgm(const std::string& path, int width, int height, const std::vector<std::uint8_t>& pixels);

}  // namespace slambox
