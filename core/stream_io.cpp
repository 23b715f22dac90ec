#include "core/stream_io.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <type_traits>
#include <utility>
#include <vector>
#include <zlib.h>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/json_io.hpp"

namespace slambox {

namespace {
constexpr char kMagic[8] = {'S', 'L', 'B', 'X', 'S', 'T', 'R', 'M'};
enum Tag : std::uint8_t { kOdometry = 1, kLaser = 2, kLandmarks = 3, kGyro = 4, kGroundTruth = 5, kEnd = 255 };
const char* kRecreate = "re-create it with `slambox simulate SCENARIO -o FILE`";

/// Format version 1's checksum: FNV-1a 64 over the bytes (one multiply per byte: ~10 ms for
/// `loop`'s 8.5 MB, which is why version 2 uses zlib's CRC-32, ~1.5 ms).
std::uint64_t Fnv1a(const std::string& bytes, size_t n) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (size_t i = 0; i < n; ++i) h = (h ^ static_cast<unsigned char>(bytes[i])) * 0x100000001b3ull;
  return h;
}

std::uint32_t Crc32(std::uint32_t crc, const char* data, size_t n) {
  return static_cast<std::uint32_t>(crc32_z(crc, reinterpret_cast<const Bytef*>(data), n));
}

/// Little-endian fields into a buffer. With a sink, every full chunk goes to the sink (its
/// CRC folded in first), so a file is written without holding all of it in memory; without
/// one, the whole serialization stays in `out`.
struct Writer {
  static constexpr size_t kChunkBytes = size_t{1} << 20;
  std::string out;
  std::ostream* sink = nullptr;
  std::uint32_t crc = Crc32(0, nullptr, 0);

  void Bytes(const void* data, size_t n) {
    out.append(static_cast<const char*>(data), n);
    if (sink && out.size() >= kChunkBytes) Drain();
  }
  template <class T>
  void Number(T v) {
    if constexpr (std::endian::native == std::endian::little) {
      Bytes(&v, sizeof v);
    } else {
      using U = std::conditional_t<sizeof(T) == 8, std::uint64_t, std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint8_t>>;
      const U u = std::bit_cast<U>(v);
      char b[sizeof(T)];
      for (size_t i = 0; i < sizeof(T); ++i) b[i] = static_cast<char>(u >> (8 * i));
      Bytes(b, sizeof b);
    }
  }
  void U8(std::uint8_t v) { Number(v); }
  void U32(std::uint32_t v) { Number(v); }
  void U64(std::uint64_t v) { Number(v); }
  void F64(double v) { Number(v); }
  void F64s(const std::vector<double>& v) {
    if constexpr (std::endian::native == std::endian::little) Bytes(v.data(), v.size() * sizeof(double));
    else for (double x : v) F64(x);
  }
  void Pose(double t, const SE2& p) { F64(t); F64(p.x); F64(p.y); F64(p.theta); }
  /// CRC of everything not yet drained, folded in; with a sink, written out and cleared (so
  /// without one, call it once, at the end).
  void Drain() {
    crc = Crc32(crc, out.data(), out.size());
    if (!sink) return;
    sink->write(out.data(), static_cast<std::streamsize>(out.size()));
    out.clear();
  }
};

struct Reader {
  const std::string& in;
  const std::string& name;
  size_t pos = 0;
  void Need(size_t n) const {
    if (in.size() - pos < n)
      throw InputError(name, 0,
                       "truncated stream file: needs " + std::to_string(n) + " more bytes at byte offset " +
                           std::to_string(pos) + " but the file ends at " + std::to_string(in.size()),
                       kRecreate);
  }
  std::uint8_t U8() { Need(1); return static_cast<std::uint8_t>(in[pos++]); }
  std::uint32_t U32() {
    Need(4);
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= static_cast<std::uint32_t>(static_cast<unsigned char>(in[pos++])) << (8 * i);
    return v;
  }
  std::uint64_t U64() {
    Need(8);
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= static_cast<std::uint64_t>(static_cast<unsigned char>(in[pos++])) << (8 * i);
    return v;
  }
  /// Every number inside a record is finite (a NaN or inf would poison every module).
  double F64() {
    const size_t at = pos;
    const double v = std::bit_cast<double>(U64());
    if (!std::isfinite(v)) Corrupt("non-finite number (" + std::to_string(v) + ") in a " + record + " record", at);
    return v;
  }
  SE2 Pose() {
    SE2 p;
    p.x = F64();
    p.y = F64();
    p.theta = F64();
    return p;
  }
  std::string record = "?";  ///< the record being read, for errors
  [[noreturn]] void Corrupt(const std::string& what, size_t at) const {
    throw InputError(name, 0, "corrupt stream file: " + what + " at byte offset " + std::to_string(at), kRecreate);
  }
};

nlohmann::json HeaderJson(const StreamHeader& h) {
  nlohmann::json j = {{"slambox_version", h.slambox_version}, {"scenario_name", h.scenario_name},
          {"scenario_yaml", h.scenario_yaml},     {"seed", h.seed},
          {"dt_s", h.dt_s},                       {"duration_s", h.duration_s},
          {"start_pose", ToJson(h.start_pose)},   {"sensors", ToJson(h.sensors)},
          {"world", ToJson(h.world)}};
  // Written only when known, so simulated streams keep their bytes (and golden hashes).
  if (h.time_origin_s) j["time_origin_s"] = *h.time_origin_s;
  return j;
}

StreamHeader HeaderFromJson(const nlohmann::json& j) {
  StreamHeader h;
  h.slambox_version = j.at("slambox_version").get<std::string>();
  h.scenario_name = j.at("scenario_name").get<std::string>();
  h.scenario_yaml = j.at("scenario_yaml").get<std::string>();
  h.seed = j.at("seed").get<std::uint64_t>();
  h.dt_s = j.at("dt_s").get<double>();
  h.duration_s = j.at("duration_s").get<double>();
  h.start_pose = SE2FromJson(j.at("start_pose"));
  h.sensors = SensorSuiteFromJson(j.at("sensors"));
  h.world = WorldFromJson(j.at("world"));
  if (j.contains("time_origin_s")) h.time_origin_s = j.at("time_origin_s").get<double>();
  return h;
}

// Magic, format version and header JSON; leaves r.pos at the first record.
StreamHeader ParseHeaderOnly(Reader& r) {
  const std::string& bytes = r.in;
  if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    throw InputError(r.name, 0, "not a slambox stream file (no stream magic at byte offset 0)",
                     "give a file written by `slambox simulate ... -o FILE`, or a scenario name or YAML file");
  r.pos = sizeof kMagic;
  const std::uint32_t version = r.U32();
  if (version != 1 && version != static_cast<std::uint32_t>(StreamHeader::kFormatVersion))
    throw InputError(r.name, 0,
                     "stream format version " + std::to_string(version) + " (byte offset 8); this slambox reads versions 1 to " +
                         std::to_string(StreamHeader::kFormatVersion),
                     std::string(kRecreate) + " using this slambox");
  StreamHeader header;
  const size_t header_at = r.pos;
  const std::uint64_t header_size = r.U64();
  r.Need(header_size);
  try {
    header = HeaderFromJson(nlohmann::json::parse(bytes.substr(r.pos, header_size)));
  } catch (const nlohmann::json::exception& e) {
    r.Corrupt(std::string("unreadable header (") + e.what() + ")", header_at);
  }
  header.format_version = static_cast<int>(version);
  r.pos += header_size;
  return header;
}

void WriteEvent(Writer& w, const SensorEvent& event) {
  std::visit(
      [&](const auto& e) {
        using E = std::decay_t<decltype(e)>;
        if constexpr (std::is_same_v<E, OdometryEvent>) {
          w.U8(kOdometry);
          w.Pose(e.t_s, e.delta);
        } else if constexpr (std::is_same_v<E, LaserScanEvent>) {
          w.U8(kLaser);
          for (double v : {e.t_s, e.angle_min_rad, e.angle_increment_rad, e.range_min_m, e.range_max_m}) w.F64(v);
          w.U32(static_cast<std::uint32_t>(e.ranges_m.size()));
          w.F64s(e.ranges_m);
          if (e.valid.size() == e.ranges_m.size()) w.Bytes(e.valid.data(), e.valid.size());
          else for (size_t i = 0; i < e.ranges_m.size(); ++i) w.U8(i < e.valid.size() ? e.valid[i] : 0);
        } else if constexpr (std::is_same_v<E, LandmarkEvent>) {
          w.U8(kLandmarks);
          w.F64(e.t_s);
          w.U32(static_cast<std::uint32_t>(e.observations.size()));
          for (const auto& o : e.observations) {
            w.F64(o.range_m);
            w.F64(o.bearing_rad);
            w.U32(static_cast<std::uint32_t>(o.id));
          }
        } else {
          w.U8(kGyro);
          w.F64(e.t_s);
          w.F64(e.yaw_rate_rps);
        }
      },
      event);
}

// Bytes WriteEvent writes for `event`: SerializeStream reserves the whole file at once
// (growing an 8 MB string by doubling cost a fifth of `slambox simulate loop`).
size_t EventBytes(const SensorEvent& event) {
  return std::visit(
      [](const auto& e) -> size_t {
        using E = std::decay_t<decltype(e)>;
        if constexpr (std::is_same_v<E, OdometryEvent>) return 1 + 4 * 8;
        else if constexpr (std::is_same_v<E, LaserScanEvent>) return 1 + 5 * 8 + 4 + 9 * e.ranges_m.size();
        else if constexpr (std::is_same_v<E, LandmarkEvent>) return 1 + 8 + 4 + 20 * e.observations.size();
        else return 1 + 2 * 8;
      },
      event);
}
}  // namespace

namespace {
/// Serializes `stream` into `w`: with a sink, in chunks; the checksum (version 2: CRC-32 of
/// every byte before it, in the low 32 bits of the u64) is written last.
void Serialize(const Stream& stream, Writer& w) {
  const std::string header = HeaderJson(stream.header).dump();
  if (!w.sink) {
    size_t bytes = sizeof kMagic + 4 + 8 + header.size() + stream.groundtruth.size() * (1 + 4 * 8) + 1 + 3 * 8;
    for (const SensorEvent& e : stream.events) bytes += EventBytes(e);
    w.out.reserve(bytes);
  }
  w.Bytes(kMagic, sizeof kMagic);
  w.U32(static_cast<std::uint32_t>(StreamHeader::kFormatVersion));
  w.U64(header.size());
  w.Bytes(header.data(), header.size());
  for (const SensorEvent& e : stream.events) WriteEvent(w, e);
  for (const StampedPose& p : stream.groundtruth) {
    w.U8(kGroundTruth);
    w.Pose(p.t_s, p.pose);
  }
  w.U8(kEnd);
  w.U64(stream.events.size());
  w.U64(stream.groundtruth.size());
  w.Drain();  // the CRC of every byte so far; with a sink, `out` is empty now
  std::ostream* sink = std::exchange(w.sink, nullptr);
  const size_t checksum_at = w.out.size();
  w.U64(w.crc);
  if (sink) sink->write(w.out.data() + checksum_at, 8);
}
}  // namespace

std::string SerializeStream(const Stream& stream) {
  Writer w;
  Serialize(stream, w);
  return std::move(w.out);
}

Stream ParseStream(const std::string& bytes, const std::string& name) {
  Reader r{bytes, name};
  Stream s;
  s.header = ParseHeaderOnly(r);
  while (true) {
    const size_t at = r.pos;
    const std::uint8_t tag = r.U8();
    if (tag == kEnd) break;
    r.record = tag == kOdometry      ? "odometry"
               : tag == kLaser       ? "laser"
               : tag == kLandmarks   ? "landmarks"
               : tag == kGyro        ? "gyro"
               : tag == kGroundTruth ? "groundtruth"
                                     : "unknown";
    if (r.record == "unknown") r.Corrupt("unknown record tag " + std::to_string(tag), at);
    const double t = r.F64();
    if (tag == kOdometry) {
      s.events.push_back(OdometryEvent{t, r.Pose()});
    } else if (tag == kGyro) {
      s.events.push_back(GyroEvent{t, r.F64()});
    } else if (tag == kGroundTruth) {
      s.groundtruth.push_back({t, r.Pose()});
    } else if (tag == kLaser) {
      LaserScanEvent e;
      e.t_s = t;
      e.angle_min_rad = r.F64();
      e.angle_increment_rad = r.F64();
      e.range_min_m = r.F64();
      e.range_max_m = r.F64();
      const std::uint32_t n = r.U32();
      r.Need(static_cast<size_t>(n) * 9);
      e.ranges_m.resize(n);
      for (auto& v : e.ranges_m) v = r.F64();
      e.valid.resize(n);
      for (auto& v : e.valid) v = r.U8();
      s.events.push_back(std::move(e));
    } else if (tag == kLandmarks) {
      LandmarkEvent e;
      e.t_s = t;
      const std::uint32_t n = r.U32();
      r.Need(static_cast<size_t>(n) * 20);
      e.observations.resize(n);
      for (auto& o : e.observations) {
        o.range_m = r.F64();
        o.bearing_rad = r.F64();
        o.id = static_cast<std::int32_t>(r.U32());
      }
      s.events.push_back(std::move(e));
    } else {
      r.Corrupt("unknown record tag " + std::to_string(tag), at);
    }
  }
  const size_t end_at = r.pos - 1;
  const std::uint64_t num_events = r.U64(), num_gt = r.U64();
  const size_t checksum_at = r.pos;
  const std::uint64_t checksum = r.U64();
  if (num_events != s.events.size() || num_gt != s.groundtruth.size())
    r.Corrupt("record counts in the end record do not match the records read", end_at);
  const std::uint64_t expected = s.header.format_version == 1 ? Fnv1a(bytes, checksum_at)
                                                               : Crc32(Crc32(0, nullptr, 0), bytes.data(), checksum_at);
  if (checksum != expected) r.Corrupt("checksum mismatch", checksum_at);
  if (r.pos != bytes.size()) r.Corrupt("unexpected bytes after the end record", r.pos);
  return s;
}

void WriteStream(const Stream& stream, const std::string& path) {
  WriteFileAtomic(path, [&](std::ostream& out) {
    Writer w;
    w.sink = &out;
    w.out.reserve(Writer::kChunkBytes + (1 << 16));
    Serialize(stream, w);
  });
}

Stream ReadStream(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw InputError(path, 0, "cannot open the stream file", "check the path");
  const std::streamoff size = in.tellg();
  if (size < 0) {  // not seekable (a pipe): read it as it comes
    in.clear();
    std::ostringstream buffer;
    buffer << in.rdbuf();
    return ParseStream(buffer.str(), path);
  }
  std::string bytes(static_cast<size_t>(size), '\0');
  in.seekg(0);
  if (!in.read(bytes.data(), size)) throw InputError(path, 0, "cannot read the stream file", "check the path");
  return ParseStream(bytes, path);
}

StreamHeader ReadStreamHeader(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot open the stream file", "check the path");
  constexpr size_t kPrefix = sizeof kMagic + 12;  // magic, u32 version, u64 header size
  std::string bytes(kPrefix, '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(kPrefix));
  bytes.resize(static_cast<size_t>(in.gcount()));
  if (bytes.size() == kPrefix) {
    std::uint64_t size = 0;
    for (int i = 0; i < 8; ++i) size |= static_cast<std::uint64_t>(static_cast<unsigned char>(bytes[12 + i])) << (8 * i);
    const size_t n = static_cast<size_t>(std::min<std::uint64_t>(size, 1ull << 30));  // the reader reports a short file
    bytes.resize(kPrefix + n);
    in.read(bytes.data() + kPrefix, static_cast<std::streamsize>(n));
    bytes.resize(kPrefix + static_cast<size_t>(in.gcount()));
  }
  Reader r{bytes, path};
  return ParseHeaderOnly(r);
}

bool IsStreamFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char head[sizeof kMagic] = {};
  if (!in.read(head, sizeof head)) return false;
  return std::memcmp(head, kMagic, sizeof kMagic) == 0;
}

nlohmann::json StreamHeaderToJson(const StreamHeader& header) { return HeaderJson(header); }

}  // namespace slambox
