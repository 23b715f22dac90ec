#pragma once
// Stream files (`slambox simulate -o FILE`): a versioned binary format. Reading a file of
// another format version, a truncated or corrupt one throws InputError naming the file
// and, where known, the byte offset.
#include <string>

#include "core/stream.hpp"

namespace slambox {

/// Writes to a temporary name in the same folder, then renames (never a partial file).
void WriteStream(const Stream& stream, const std::string& path);
Stream ReadStream(const std::string& path);
/// True if the file starts with the stream magic (so commands can tell streams from scenarios).
bool IsStreamFile(const std::string& path);

}  // namespace slambox
