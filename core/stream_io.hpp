#pragma once
// Stream files (`slambox simulate -o FILE`): a versioned binary format. Reading a file of
// another format version, a truncated or corrupt one throws InputError naming the file
// and, where known, the byte offset.
//
// Layout (every number little-endian; f64 = IEEE-754 bits):
//   "SLBXSTRM" | u32 format version | u64 n, n bytes of header JSON (StreamHeader)
//   records, each a u8 tag then its fields:
//     1 odometry   f64 t, x, y, theta
//     2 laser      f64 t, angle_min, angle_increment, range_min, range_max,
//                  u32 n, n x f64 range, n x u8 valid
//     3 landmarks  f64 t, u32 n, n x (f64 range, f64 bearing, i32 id)
//     4 gyro       f64 t, yaw_rate
//     5 groundtruth f64 t, x, y, theta
//   255 end      u64 number of events, u64 number of ground-truth poses,
//                u64 checksum of every byte before it: version 2, zlib's CRC-32 (in the
//                low 32 bits); version 1 (still read), FNV-1a 64 — a tenth of the speed
#include <nlohmann/json.hpp>
#include <string>

#include "core/stream.hpp"

namespace slambox {

/// Writes to a temporary name in the same folder, then renames (never a partial file).
void WriteStream(const Stream& stream, const std::string& path);
Stream ReadStream(const std::string& path);
/// Only the header (no events are read or checked): for a converted log's time origin.
StreamHeader ReadStreamHeader(const std::string& path);
/// The header as written in the file (JSON): the Python module's `Stream.header` dict.
nlohmann::json StreamHeaderToJson(const StreamHeader& header);
/// True if the file starts with the stream magic (so commands can tell streams from scenarios).
bool IsStreamFile(const std::string& path);

/// The file's bytes, in memory (for hashing in determinism tests).
std::string SerializeStream(const Stream& stream);
/// Parses bytes written by SerializeStream; `name` is used in error messages.
Stream ParseStream(const std::string& bytes, const std::string& name);

}  // namespace slambox
