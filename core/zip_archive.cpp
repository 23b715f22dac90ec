#include "core/zip_archive.hpp"

#include <zlib.h>

#include <cassert>
#include <cstdint>
#include <fstream>
#include <iterator>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace slambox {

namespace {

constexpr std::uint32_t kLocalSig = 0x04034b50, kCentralSig = 0x02014b50, kEndSig = 0x06054b50;
constexpr std::uint16_t kDosDate1980 = (0 << 9) | (1 << 5) | 1;  // 1980-01-01

void U16(std::string& out, std::uint32_t v) {
  out.push_back(static_cast<char>(v & 0xff));
  out.push_back(static_cast<char>((v >> 8) & 0xff));
}
void U32(std::string& out, std::uint32_t v) {
  U16(out, v & 0xffff);
  U16(out, v >> 16);
}
std::uint32_t Get(const std::string& s, std::size_t at, int bytes) {
  std::uint32_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(s[at + i]);
  return v;
}
std::uint32_t Crc32(const std::string& bytes) {
  return static_cast<std::uint32_t>(
      crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(bytes.data()), static_cast<uInt>(bytes.size())));
}

// The fields a local header and a central-directory record share (version needed .. name length).
void CommonFields(std::string& out, const ZipEntry& e, std::uint32_t crc) {
  U16(out, 20);  // version needed: 2.0
  U16(out, 0);   // flags
  U16(out, 0);   // method: stored
  U16(out, 0);   // DOS time 00:00
  U16(out, kDosDate1980);
  U32(out, crc);
  U32(out, static_cast<std::uint32_t>(e.bytes.size()));  // compressed size
  U32(out, static_cast<std::uint32_t>(e.bytes.size()));  // uncompressed size
  U16(out, static_cast<std::uint32_t>(e.name.size()));
  U16(out, 0);  // extra field length
}

}  // namespace

std::string ZipStored(const std::vector<ZipEntry>& entries) {
  std::string out, central;
  for (const auto& e : entries) {
    assert(e.bytes.size() < 0xffffffffull && e.name.size() < 0xffff);
    const std::uint32_t crc = Crc32(e.bytes);
    const auto offset = static_cast<std::uint32_t>(out.size());
    U32(out, kLocalSig);
    CommonFields(out, e, crc);
    out += e.name;
    out += e.bytes;
    U32(central, kCentralSig);
    U16(central, 20);  // version made by: 2.0, MS-DOS attributes
    CommonFields(central, e, crc);
    U16(central, 0);  // comment length
    U16(central, 0);  // disk number
    U16(central, 0);  // internal attributes
    U32(central, 0);  // external attributes
    U32(central, offset);
    central += e.name;
  }
  const auto central_offset = static_cast<std::uint32_t>(out.size());
  out += central;
  U32(out, kEndSig);
  U16(out, 0);  // this disk
  U16(out, 0);  // disk with the central directory
  U16(out, static_cast<std::uint32_t>(entries.size()));
  U16(out, static_cast<std::uint32_t>(entries.size()));
  U32(out, static_cast<std::uint32_t>(central.size()));
  U32(out, central_offset);
  U16(out, 0);  // comment length
  return out;
}

void WriteZipStored(const std::string& path, const std::vector<ZipEntry>& entries) {
  WriteFileAtomic(path, ZipStored(entries));
}

std::vector<ZipEntry> ReadZipStored(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot open the archive", "check the path");
  const std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string fix = "write the archive with slambox or Python's zipfile (stored entries)";
  if (s.size() < 22 || Get(s, s.size() - 22, 4) != kEndSig)
    throw InputError(path, 0, "no ZIP end record (or an archive comment)", fix);
  const std::size_t end = s.size() - 22;
  const std::uint32_t count = Get(s, end + 10, 2), central_size = Get(s, end + 12, 4), central_at = Get(s, end + 16, 4);
  if (std::size_t(central_at) + central_size > end) throw InputError(path, 0, "central directory out of range", fix);
  std::vector<ZipEntry> entries;
  std::size_t p = central_at;
  for (std::uint32_t i = 0; i < count; ++i) {
    if (p + 46 > end || Get(s, p, 4) != kCentralSig) throw InputError(path, 0, "malformed central directory", fix);
    const std::uint32_t method = Get(s, p + 10, 2), crc = Get(s, p + 16, 4), size = Get(s, p + 20, 4);
    const std::uint32_t name_len = Get(s, p + 28, 2), extra_len = Get(s, p + 30, 2), comment_len = Get(s, p + 32, 2);
    const std::uint32_t local = Get(s, p + 42, 4);
    if (p + 46 + name_len > end) throw InputError(path, 0, "malformed central directory", fix);
    ZipEntry e{s.substr(p + 46, name_len), {}};
    if (method != 0) throw InputError(path, 0, "entry '" + e.name + "' is compressed", fix);
    if (std::size_t(local) + 30 > s.size() || Get(s, local, 4) != kLocalSig)
      throw InputError(path, 0, "malformed local header of '" + e.name + "'", fix);
    const std::size_t data = local + 30 + Get(s, local + 26, 2) + Get(s, local + 28, 2);
    if (data + size > s.size()) throw InputError(path, 0, "truncated entry '" + e.name + "'", fix);
    e.bytes = s.substr(data, size);
    if (Crc32(e.bytes) != crc) throw InputError(path, 0, "CRC mismatch in '" + e.name + "'", fix);
    entries.push_back(std::move(e));
    p += 46 + name_len + extra_len + comment_len;
  }
  return entries;
}

}  // namespace slambox
