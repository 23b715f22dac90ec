#include "datasets/compressed_file.hpp"

#include <bzlib.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "core/limits.hpp"

namespace slambox {

namespace {

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

[[noreturn]] void TooBig(const std::string& path, std::uint64_t max_bytes) {
  throw InputError(path, 0,
                   "holds (decompressed) more than " + std::to_string(max_bytes) +
                       " bytes (the limit; public CARMEN logs are tens of MB)",
                   "check that this is the log you meant; split it if it really is that large");
}

std::string ReadGzip(const std::string& path, std::uint64_t max_bytes) {
  gzFile f = gzopen(path.c_str(), "rb");
  if (!f) throw InputError(path, 0, "cannot open the file", "check the path and its permissions");
  std::string out;
  char buffer[1 << 16];
  int n = 0;
  while ((n = gzread(f, buffer, sizeof buffer)) > 0) {
    out.append(buffer, static_cast<size_t>(n));
    if (out.size() > max_bytes) {
      gzclose(f);
      TooBig(path, max_bytes);
    }
  }
  int code = Z_OK;
  const std::string message = n < 0 ? gzerror(f, &code) : "";
  gzclose(f);
  if (n < 0)
    throw InputError(path, 0, "corrupt gzip data (" + message + ")", "download the log again or decompress it with gunzip to see the damage");
  return out;
}

std::string ReadPlain(const std::string& path, std::uint64_t max_bytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot open the file", "check the path and its permissions");
  std::error_code error;
  const auto bytes = std::filesystem::file_size(path, error);
  if (!error && bytes > max_bytes) TooBig(path, max_bytes);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string ReadBzip2(const std::string& path, std::uint64_t max_bytes) {
  std::string packed = ReadPlain(path, max_bytes);
  std::string out;
  char buffer[1 << 16];
  size_t consumed = 0;
  // A .bz2 may hold several concatenated streams (pbzip2): decode them one after another.
  while (consumed < packed.size()) {
    bz_stream z{};
    if (BZ2_bzDecompressInit(&z, 0, 0) != BZ_OK) throw InputError(path, 0, "libbz2 could not start", "");
    z.next_in = packed.data() + consumed;
    z.avail_in = static_cast<unsigned>(packed.size() - consumed);
    int code = BZ_OK;
    while (code == BZ_OK) {
      z.next_out = buffer;
      z.avail_out = sizeof buffer;
      code = BZ2_bzDecompress(&z);
      out.append(buffer, sizeof buffer - z.avail_out);
      if (out.size() > max_bytes) {
        BZ2_bzDecompressEnd(&z);
        TooBig(path, max_bytes);
      }
      if (code == BZ_OK && z.avail_in == 0 && z.avail_out > 0) break;  // input ended inside a stream
    }
    consumed = packed.size() - z.avail_in;
    BZ2_bzDecompressEnd(&z);
    if (code != BZ_STREAM_END)
      throw InputError(path, 0, "corrupt or truncated bzip2 data", "download the log again or test it with `bzip2 -t`");
  }
  if (out.empty()) throw InputError(path, 0, "empty bzip2 file", "give a .bz2 file made by bzip2");
  return out;
}

}  // namespace

std::string ReadMaybeCompressedFile(const std::string& path, std::uint64_t max_bytes) {
  if (EndsWith(path, ".gz")) return ReadGzip(path, max_bytes);
  if (EndsWith(path, ".bz2")) return ReadBzip2(path, max_bytes);
  return ReadPlain(path, max_bytes);
}

}  // namespace slambox
