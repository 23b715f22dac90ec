#pragma once
// ZIP archives of stored (uncompressed) entries, as Python's zipfile writes by default
// (ZIP_STORED) and reads: local headers, central directory, end record; CRC-32 from zlib.
// Deterministic: every entry carries the DOS date 1980-01-01 00:00. No ZIP64 (< 4 GiB).
#include <string>
#include <vector>

namespace slambox {

struct ZipEntry {
  std::string name;   ///< path inside the archive, '/' separated
  std::string bytes;  ///< content
};

/// The archive's bytes. Asserts unique names and sizes below 4 GiB.
std::string ZipStored(const std::vector<ZipEntry>& entries);

/// Writes ZipStored(entries) to `path` atomically.
void WriteZipStored(const std::string& path, const std::vector<ZipEntry>& entries);

/// Entries of an archive of stored entries (what ZipStored writes). Throws InputError on
/// a malformed archive, a compressed entry or a CRC mismatch. For tests and tools.
std::vector<ZipEntry> ReadZipStored(const std::string& path);

}  // namespace slambox
