#pragma once
// Reads a whole log file into memory, decompressing by its suffix: `.gz` (zlib), `.bz2`
// (libbz2), anything else as it is. Public logs are shipped compressed; they are a few
// tens of MB uncompressed, so reading them whole keeps the parsers simple.
#include <cstdint>
#include <string>

#include "core/limits.hpp"

namespace slambox {

/// Throws InputError naming the file when it cannot be opened, is corrupt, or holds
/// (decompressed) more than `max_bytes` — checked while decompressing, so a small file
/// that inflates without end (a "zip bomb") is refused after max_bytes, not after the
/// memory is gone.
std::string ReadMaybeCompressedFile(const std::string& path,
                                    std::uint64_t max_bytes = limits::kMaxDecompressedBytes);

}  // namespace slambox
