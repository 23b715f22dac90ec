#pragma once
// Result files are never left half-written: write to a temporary name in the same
// folder, flush, then rename over the target (atomic on POSIX file systems).
#include <functional>
#include <ostream>
#include <string>

namespace slambox {

/// Calls `write` with a stream to a temporary file, then renames it to `path`.
/// Creates missing parent folders. Throws std::runtime_error on I/O failure (and removes
/// the temporary file).
void WriteFileAtomic(const std::string& path, const std::function<void(std::ostream&)>& write);
void WriteFileAtomic(const std::string& path, const std::string& content);

}  // namespace slambox
