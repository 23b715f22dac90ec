#pragma once
// Reads a whole log file into memory, decompressing by its suffix: `.gz` (zlib), `.bz2`
// (libbz2), anything else as it is. Public logs are shipped compressed; they are a few
// tens of MB uncompressed, so reading them whole keeps the parsers simple.
#include <string>

namespace slambox {

/// Throws InputError naming the file when it cannot be opened or is corrupt.
std::string ReadMaybeCompressedFile(const std::string& path);

}  // namespace slambox
