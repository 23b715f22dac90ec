#include "core/stream_io.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <zlib.h>

#include "core/error.hpp"
#include "core/json_io.hpp"
#include "tests/support/slambox_cli.hpp"
#include "tests/support/synthetic_stream.hpp"

namespace slambox {
namespace {

Stream SmallStream() {
  testing::SyntheticOptions o;
  o.path = {{0, 0}, {3, 0}, {3, 2}};
  o.sensors.odometry = OdometryConfig{};
  o.sensors.landmarks = LandmarkSensorConfig{.detection_prob_known = false};
  o.sensors.lidar = LidarConfig{.beams = 36, .range_max_m = 8};
  o.sensors.gyro = GyroConfig{.rate_hz = 25, .sigma_dps = 0.2, .bias_dps = -0.1};
  World w;
  w.wall_segments = {{{-1, -1}, {5, -1}}, {{5, -1}, {5, 4}}};
  w.wall_circles = {{{2, 3}, 0.25}};
  w.landmarks = {{0, {1, 1}, 0.1}, {4, {2, -0.5}, 0.1}};
  w.movers = {{{{0, 3}, {4, 3}}, 0.3, {0, 0}}};
  Stream s = testing::MakeSyntheticStream(o, w);
  s.header.slambox_version = "0.1.0";
  s.header.scenario_yaml = "version: 1\nname: synthetic\n";
  s.header.seed = 0xFFFFFFFFFFFFFFF1ull;  // the full uint64 range survives
  s.events.push_back(GyroEvent{s.header.duration_s, -0.0123456789});
  for (auto& e : s.events)
    if (auto* lm = std::get_if<LandmarkEvent>(&e)) {
      lm->observations.push_back({3.25, -1.5, -1});  // clutter id
      break;
    }
  return s;
}

std::string TempPath(const std::string& name) {
  static const std::filesystem::path dir = testing::FreshTempDir("stream_io");
  return (dir / name).string();
}

void WriteBytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::string ErrorOf(const std::string& path) {
  try {
    ReadStream(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(StreamIo, FileRoundTripIsBitIdentical) {
  const Stream s = SmallStream();
  const std::string path = TempPath("round_trip.stream");
  WriteStream(s, path);
  EXPECT_TRUE(IsStreamFile(path));
  const Stream r = ReadStream(path);
  EXPECT_EQ(SerializeStream(r), SerializeStream(s));
  ASSERT_EQ(r.events.size(), s.events.size());
  ASSERT_EQ(r.groundtruth.size(), s.groundtruth.size());
  EXPECT_EQ(r.header.seed, s.header.seed);
  EXPECT_EQ(r.header.scenario_yaml, s.header.scenario_yaml);
  EXPECT_EQ(r.header.sensors.lidar->beams, 36);
  EXPECT_EQ(r.header.sensors.gyro->bias_dps, -0.1);
  EXPECT_FALSE(r.header.sensors.landmarks->detection_prob_known);
  EXPECT_EQ(r.header.world.movers.at(0).radius_m, 0.3);
  for (size_t i = 0; i < s.events.size(); ++i) ASSERT_EQ(r.events[i].index(), s.events[i].index());
  for (size_t i = 0; i < s.groundtruth.size(); ++i)
    EXPECT_EQ(std::memcmp(&r.groundtruth[i], &s.groundtruth[i], sizeof(StampedPose)), 0);
  const auto lm = std::find_if(r.events.begin(), r.events.end(),
                               [](const SensorEvent& e) { return std::holds_alternative<LandmarkEvent>(e); });
  ASSERT_NE(lm, r.events.end());
  EXPECT_EQ(std::get<LandmarkEvent>(*lm).observations.back().id, -1);
  EXPECT_EQ(std::get<GyroEvent>(r.events.back()).yaw_rate_rps, -0.0123456789);
}

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::uint64_t LittleEndianU64(const std::string& bytes, size_t at) {
  std::uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v |= static_cast<std::uint64_t>(static_cast<unsigned char>(bytes[at + i])) << (8 * i);
  return v;
}

TEST(StreamIo, AFileWrittenInChunksIsTheSerializationAndItsChecksumIsCrc32) {
  Stream s = SmallStream();
  LaserScanEvent big;  // one scan over the writer's 1 MiB chunk, and many small records
  big.t_s = s.header.duration_s;
  big.range_max_m = 10.0;
  for (int i = 0; i < 200000; ++i) {
    big.ranges_m.push_back(0.5 + 1e-5 * i);
    big.valid.push_back(static_cast<std::uint8_t>(i % 3 != 0));
  }
  s.events.push_back(big);
  for (int k = 0; k < 40000; ++k) s.groundtruth.push_back({s.header.duration_s + 1e-3 * k, SE2(k, -k, 0.1)});
  const std::string path = TempPath("chunks.stream");
  WriteStream(s, path);
  const std::string bytes = ReadBytes(path), expected = SerializeStream(s);
  ASSERT_GT(bytes.size(), std::size_t{2} << 20);
  EXPECT_TRUE(bytes == expected);
  // The trailer's checksum is zlib's CRC-32 of every byte before it.
  const std::uint64_t crc = crc32_z(0, reinterpret_cast<const Bytef*>(bytes.data()), bytes.size() - 8);
  EXPECT_EQ(LittleEndianU64(bytes, bytes.size() - 8), crc);
  EXPECT_EQ(SerializeStream(ReadStream(path)), expected);
}

// A header written before detection_prob_known existed states its P_D (the default).
TEST(StreamIo, HeadersWithoutDetectionProbKnownStateTheirPd) {
  nlohmann::json j = ToJson(SmallStream().header.sensors);
  ASSERT_FALSE(SensorSuiteFromJson(j).landmarks->detection_prob_known);
  j.at("landmarks").erase("detection_prob_known");
  EXPECT_TRUE(SensorSuiteFromJson(j).landmarks->detection_prob_known);
}

TEST(StreamIo, VersionOneFilesAreStillRead) {
  // Version 1 = the same layout with an FNV-1a 64 checksum: made here from a version 2 file.
  const Stream s = SmallStream();
  std::string bytes = SerializeStream(s);
  bytes[8] = 1;
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (size_t i = 0; i + 8 < bytes.size(); ++i) h = (h ^ static_cast<unsigned char>(bytes[i])) * 0x100000001b3ull;
  for (int i = 0; i < 8; ++i) bytes[bytes.size() - 8 + i] = static_cast<char>(h >> (8 * i));
  const std::string path = TempPath("version1.stream");
  WriteBytes(path, bytes);
  const Stream r = ReadStream(path);
  EXPECT_EQ(r.header.format_version, 1);
  EXPECT_EQ(SerializeStream(r), SerializeStream(s));  // written back as version 2
  bytes[bytes.size() - 1] ^= 1;  // and a version 1 checksum is checked
  WriteBytes(path, bytes);
  EXPECT_NE(ErrorOf(path).find("checksum mismatch"), std::string::npos);
}

TEST(StreamIo, TimeOriginIsWrittenOnlyWhenKnownAndReadBack) {
  Stream s = SmallStream();
  const std::string plain = SerializeStream(s);
  EXPECT_EQ(plain.find("time_origin_s"), std::string::npos);  // simulated streams keep their bytes
  EXPECT_FALSE(ParseStream(plain, "plain").header.time_origin_s.has_value());
  s.header.time_origin_s = 976052905.167303;  // an ipc timestamp: every digit must survive
  const std::string path = TempPath("origin.stream");
  WriteStream(s, path);
  const Stream r = ReadStream(path);
  ASSERT_TRUE(r.header.time_origin_s.has_value());
  EXPECT_EQ(*r.header.time_origin_s, 976052905.167303);
  const StreamHeader h = ReadStreamHeader(path);
  ASSERT_TRUE(h.time_origin_s.has_value());
  EXPECT_EQ(*h.time_origin_s, 976052905.167303);
  EXPECT_EQ(h.seed, s.header.seed);
  EXPECT_EQ(h.sensors.lidar->beams, 36);
  // The header reader checks what it reads: magic, and a file cut inside the header.
  const std::string bytes = SerializeStream(s);
  WriteBytes(path, bytes.substr(0, 40));
  EXPECT_THROW(ReadStreamHeader(path), InputError);
  WriteBytes(path, "not a stream at all");
  EXPECT_THROW(ReadStreamHeader(path), InputError);
}

TEST(StreamIo, TruncatedFileNamesFileAndOffset) {
  const std::string bytes = SerializeStream(SmallStream());
  const std::string path = TempPath("truncated.stream");
  for (size_t keep : {size_t{5}, size_t{40}, bytes.size() / 2, bytes.size() - 1}) {
    WriteBytes(path, bytes.substr(0, keep));
    const std::string err = ErrorOf(path);
    EXPECT_NE(err.find(path), std::string::npos) << err;
    EXPECT_TRUE(err.find("truncated") != std::string::npos || err.find("not a slambox stream") != std::string::npos) << err;
    if (keep > 12) {
      EXPECT_NE(err.find("byte offset"), std::string::npos) << err;
    }
    EXPECT_NE(err.find("fix:"), std::string::npos) << err;
  }
}

TEST(StreamIo, WrongVersionAndWrongMagicAreClearErrors) {
  std::string bytes = SerializeStream(SmallStream());
  const std::string path = TempPath("version.stream");
  bytes[8] = 7;  // format version 7
  WriteBytes(path, bytes);
  const std::string err = ErrorOf(path);
  EXPECT_NE(err.find("format version 7"), std::string::npos) << err;
  EXPECT_NE(err.find("reads versions 1 to 2"), std::string::npos) << err;
  WriteBytes(path, "version: 1\nname: loop\n");
  EXPECT_FALSE(IsStreamFile(path));
  EXPECT_NE(ErrorOf(path).find("not a slambox stream"), std::string::npos);
}

TEST(StreamIo, CorruptionIsDetected) {
  const std::string bytes = SerializeStream(SmallStream());
  const std::string path = TempPath("corrupt.stream");
  for (size_t at : {bytes.size() / 3, bytes.size() / 2, bytes.size() - 30}) {
    std::string bad = bytes;
    bad[at] = static_cast<char>(bad[at] ^ 0x5A);
    WriteBytes(path, bad);
    const std::string err = ErrorOf(path);
    EXPECT_FALSE(err.empty()) << "flip at " << at;
    EXPECT_NE(err.find("byte offset"), std::string::npos) << err;
  }
}

TEST(StreamIo, NonFiniteValueInAValidFrameIsRefused) {
  // A NaN (or an infinity) planted in each kind of record, with a correct checksum: the
  // frame is valid, the number is not.
  for (const double bad : {std::nan(""), std::numeric_limits<double>::infinity()}) {
    for (const char* kind : {"odometry", "laser", "landmarks", "gyro", "groundtruth"}) {
      Stream s = SmallStream();
      const std::string k = kind;
      if (k == "groundtruth") {
        s.groundtruth[s.groundtruth.size() / 2].pose.theta = bad;
      } else {
        for (auto& e : s.events) {
          if (auto* o = std::get_if<OdometryEvent>(&e); o && k == "odometry") { o->delta.x = bad; break; }
          if (auto* l = std::get_if<LaserScanEvent>(&e); l && k == "laser") { l->ranges_m[7] = bad; break; }
          if (auto* m = std::get_if<LandmarkEvent>(&e); m && k == "landmarks" && !m->observations.empty()) {
            m->observations[0].bearing_rad = bad;
            break;
          }
          if (auto* g = std::get_if<GyroEvent>(&e); g && k == "gyro") { g->yaw_rate_rps = bad; break; }
        }
      }
      const std::string path = TempPath("nan.stream");
      WriteStream(s, path);
      const std::string err = ErrorOf(path);
      EXPECT_NE(err.find(path), std::string::npos) << kind << ": " << err;
      EXPECT_NE(err.find(std::string("non-finite number (") + (std::isnan(bad) ? "nan" : "inf") + ") in a " + k + " record"),
                std::string::npos)
          << err;
      EXPECT_NE(err.find("byte offset"), std::string::npos) << err;
    }
  }
}

}  // namespace
}  // namespace slambox
