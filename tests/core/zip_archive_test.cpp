#include "core/zip_archive.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "core/npy.hpp"

namespace slambox {
namespace {

namespace fs = std::filesystem;

TEST(ZipArchive, RoundTripsEntriesAndIsDeterministic) {
  const fs::path p = fs::temp_directory_path() / ("slambox_zip_" + std::to_string(::getpid()) + ".zip");
  const std::vector<ZipEntry> entries = {{"info.json", "{\"a\": 1}"}, {"empty", ""}, {"bin", std::string("\0\xff\x01", 3)}};
  WriteZipStored(p.string(), entries);
  const auto back = ReadZipStored(p.string());
  ASSERT_EQ(back.size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(back[i].name, entries[i].name);
    EXPECT_EQ(back[i].bytes, entries[i].bytes);
  }
  EXPECT_EQ(ZipStored(entries), ZipStored(entries));
  // CRC-32 of "123456789" is 0xCBF43926 (the standard check value), at offset 14 of the local header.
  const std::string z = ZipStored({{"c", "123456789"}});
  EXPECT_EQ(z.substr(14, 4), std::string("\x26\x39\xf4\xcb", 4));
  // A flipped content byte fails the CRC check.
  std::string bad = ZipStored(entries);
  bad[30 + 9] ^= 1;  // first byte of info.json's content
  std::ofstream(p, std::ios::binary) << bad;
  EXPECT_THROW(ReadZipStored(p.string()), InputError);
  std::ofstream(p, std::ios::binary) << "not a zip";
  EXPECT_THROW(ReadZipStored(p.string()), InputError);
  fs::remove(p);
}

TEST(Npy, HeaderIsVersion1AlignedTo64AndDataIsLittleEndianDoubles) {
  const std::string npy = NpyFloat64({1.5, -2.0, 3.25});
  ASSERT_EQ(npy.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
  const std::size_t header_len = static_cast<unsigned char>(npy[8]) | (static_cast<unsigned char>(npy[9]) << 8);
  EXPECT_EQ((10 + header_len) % 64, 0u);
  const std::string header = npy.substr(10, header_len);
  EXPECT_EQ(header.rfind("{'descr': '<f8', 'fortran_order': False, 'shape': (3,), }", 0), 0u) << header;
  EXPECT_EQ(header.back(), '\n');
  ASSERT_EQ(npy.size(), 10 + header_len + 3 * 8);
  double v[3];
  std::memcpy(v, npy.data() + 10 + header_len, sizeof v);
  EXPECT_EQ(v[0], 1.5);
  EXPECT_EQ(v[1], -2.0);
  EXPECT_EQ(v[2], 3.25);
  EXPECT_NE(NpyFloat64Matrix(std::vector<double>(16, 0.0), 4, 4).find("'shape': (4, 4), }"), std::string::npos);
  EXPECT_NE(NpyFloat64({}).find("'shape': (0,), }"), std::string::npos);
}

}  // namespace
}  // namespace slambox
