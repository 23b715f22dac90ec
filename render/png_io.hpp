#pragma once
// 8-bit RGB images and their PNG encoding (libpng).
#include <cstdint>
#include <string>
#include <vector>

namespace slambox::render {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  ///< row-major from the top row, 3 bytes per pixel
  const std::uint8_t* At(int x, int y) const { return &rgb[(static_cast<size_t>(y) * width + x) * 3]; }
};

/// PNG bytes of `image` (deterministic: no timestamp chunk).
std::vector<std::uint8_t> EncodePng(const Image& image);
/// Writes `image` to `path` atomically (core/atomic_file.hpp).
void WritePng(const std::string& path, const Image& image);
/// Reads an 8-bit RGB or RGBA PNG (alpha dropped). Throws InputError on a bad file.
Image ReadPng(const std::string& path);

}  // namespace slambox::render
