#include "slam/mrpt/mrpt_rawlog.hpp"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/serialization/CArchive.h>
#include <stdexcept>
#include <vector>
#include <zlib.h>

#include "core/error.hpp"
#include "core/file_status.hpp"
#include "core/limits.hpp"
#include "slam/mrpt/mrpt_convert.hpp"

namespace slambox::mrpt_bridge {

namespace {

/// [m] how far a later scan's sensor position may be from the first's: converted logs
/// compute it per scan from rounded poses (MOLA's fr079.rawlog: 1e-6 m apart).
constexpr double kMountToleranceM = 0.01;
constexpr const char* kFix = "give an MRPT rawlog (CRawlog, RawLogViewer's format; optionally gzip-compressed)";

double Seconds(const mrpt::Clock::time_point& t) { return mrpt::Clock::toDouble(t); }

SE2 Planar(const mrpt::poses::CPose3D& p) { return {p.x(), p.y(), p.yaw()}; }

struct Reader {
  const std::string& path;
  LaserLog log;
  SE2 odometry_pose;               ///< composed from actions (the sensory-frame layout)
  bool have_scan_mount = false;
  mrpt::poses::CPose3D scan_mount;  ///< the first scan's sensor pose

  void Fail(const std::string& problem, std::size_t index) const {
    throw InputError(path, 0, "object " + std::to_string(index) + ": " + problem, kFix);
  }

  void Observation(const mrpt::obs::CObservation& o, std::size_t index) {
    const double ts = Seconds(o.timestamp);
    if (!std::isfinite(ts) || std::abs(ts) > limits::kMaxTimestampS) Fail("timestamp out of range", index);
    if (const auto* odo = dynamic_cast<const mrpt::obs::CObservationOdometry*>(&o)) {
      log.odometry.push_back({ts, FromMrpt(odo->odometry)});
    } else if (const auto* scan = dynamic_cast<const mrpt::obs::CObservation2DRangeScan*>(&o)) {
      if (scan->getScanSize() > static_cast<std::size_t>(limits::kMaxLidarBeams))
        Fail("a scan of " + std::to_string(scan->getScanSize()) + " beams (at most " + std::to_string(limits::kMaxLidarBeams) + ")", index);
      if (!have_scan_mount) {
        scan_mount = scan->sensorPose;
        have_scan_mount = true;
        log.T_robot_laser = {scan_mount.x(), scan_mount.y(), 0.0};  // yaw stays in the beam angles
      } else if (std::abs(scan->sensorPose.x() - scan_mount.x()) > kMountToleranceM ||
                 std::abs(scan->sensorPose.y() - scan_mount.y()) > kMountToleranceM) {
        Fail("the laser's sensor pose moves between scans, from (" + std::to_string(scan_mount.x()) + ", " +
                 std::to_string(scan_mount.y()) + ") to (" + std::to_string(scan->sensorPose.x()) + ", " +
                 std::to_string(scan->sensorPose.y()) + ") (slambox streams have one laser mounting)",
             index);
      }
      // FromMrptScan gives angles in the robot frame (sensor yaw included); the laser frame
      // shares the robot's heading here, so they are the laser's angles too.
      const LaserScanEvent e = FromMrptScan(*scan, ts);
      log.scans.push_back({ts, e.angle_min_rad, e.angle_increment_rad, static_cast<double>(scan->maxRange), e.ranges_m, e.valid});
    } else if (const auto* br = dynamic_cast<const mrpt::obs::CObservationBearingRange*>(&o)) {
      const SE2 T_robot_sensor = Planar(br->sensorLocationOnRobot);
      LaserLog::Landmarks l{ts, {}};
      for (const auto& m : br->sensedData) {
        const Eigen::Vector2d p = T_robot_sensor * Eigen::Vector2d(m.range * std::cos(m.yaw), m.range * std::sin(m.yaw));
        const bool at_origin = T_robot_sensor.x == 0 && T_robot_sensor.y == 0 && T_robot_sensor.theta == 0;
        l.observations.push_back({at_origin ? double(m.range) : p.norm(),
                                  at_origin ? double(m.yaw) : std::atan2(p.y(), p.x()), m.landmarkID < 0 ? -1 : m.landmarkID});
      }
      if (!log.landmark_sensor) {
        LandmarkSensorConfig c;
        c.range_max_m = br->maxSensorDistance;
        c.fov_deg = br->fieldOfView_yaw * 180.0 / M_PI;
        c.sigma_range_m = br->sensor_std_range;
        c.sigma_bearing_deg = br->sensor_std_yaw * 180.0 / M_PI;
        c.known_ids = false;
        c.detection_prob_known = false;  // CObservationBearingRange does not carry it
        log.landmark_sensor = c;
      }
      for (const auto& obs : l.observations) log.landmark_sensor->known_ids |= obs.id >= 0;
      log.landmarks.push_back(std::move(l));
    }
  }

  void Action(const mrpt::obs::CActionCollection& actions, std::size_t index) {
    const auto move = actions.getBestMovementEstimation();
    if (!move) return;
    mrpt::poses::CPose2D increment;
    move->poseChange->getMean(increment);
    if (log.odometry.empty()) log.odometry.push_back({Seconds(move->timestamp), odometry_pose});
    odometry_pose = odometry_pose * FromMrpt(increment);
    const double ts = Seconds(move->timestamp);
    if (!std::isfinite(ts) || std::abs(ts) > limits::kMaxTimestampS) Fail("action timestamp out of range", index);
    log.odometry.push_back({ts, odometry_pose});
  }
};

/// The file's bytes, gunzipped when it is gzip-compressed (MRPT writes rawlogs either way;
/// zlib's gzread passes an uncompressed file through), refused once more than `max_bytes`
/// have come out, so a small file that inflates without end never fills the memory.
std::string ReadRawlogBytes(const std::string& path, std::uint64_t max_bytes) {
  gzFile file = gzopen(path.c_str(), "rb");
  if (file == nullptr) throw InputError(path, 0, "cannot open the rawlog", "check the path and its permissions");
  std::string bytes;
  std::vector<char> chunk(1 << 20);
  for (;;) {
    const int got = gzread(file, chunk.data(), static_cast<unsigned>(chunk.size()));
    if (got < 0) {
      int code = 0;
      const std::string why = gzerror(file, &code);
      gzclose(file);
      throw InputError(path, 0, "corrupt compressed data (zlib: " + why + ")", kFix);
    }
    if (got == 0) break;
    if (bytes.size() + static_cast<std::size_t>(got) > max_bytes) {
      gzclose(file);
      throw InputError(path, 0, "more than " + std::to_string(max_bytes) + " bytes (decompressed)",
                       "split the rawlog (RawLogViewer or rawlog-edit --cut)");
    }
    bytes.append(chunk.data(), static_cast<std::size_t>(got));
  }
  gzclose(file);
  return bytes;
}

}  // namespace

LaserLog ParseRawlog(const std::string& bytes, const std::string& path) {
  // Objects are read one at a time from memory (what CRawlog::loadFromRawLogFile does from
  // the file), so only the converted log is kept, not every MRPT object at once.
  mrpt::io::CMemoryStream memory;
  memory.assignMemoryNotOwn(bytes.data(), bytes.size());
  auto archive = mrpt::serialization::archiveFrom(memory);
  Reader r{path, {}, {}, false, {}};
  r.log.format = "MRPT rawlog";
  std::size_t index = 0;
  for (;; ++index) {
    const std::uint64_t start = memory.getPosition();
    if (start >= bytes.size()) break;
    mrpt::serialization::CSerializable::Ptr object;
    try {
      object = archive.ReadObject();
    } catch (const mrpt::serialization::CExceptionEOF&) {
      r.Fail("truncated: the file ends inside it (byte " + std::to_string(start) + " of " +
                 std::to_string(bytes.size()) + ")",
             index);
    } catch (const std::exception& e) {
      r.Fail(std::string("MRPT cannot read it: ") + e.what(), index);
    }
    if (auto frame = std::dynamic_pointer_cast<mrpt::obs::CSensoryFrame>(object)) {
      for (const auto& o : *frame)
        if (o) r.Observation(*o, index);
    } else if (auto observation = std::dynamic_pointer_cast<mrpt::obs::CObservation>(object)) {
      r.Observation(*observation, index);
    } else if (auto action = std::dynamic_pointer_cast<mrpt::obs::CActionCollection>(object)) {
      r.Action(*action, index);
    }
    if (r.log.scans.size() + r.log.odometry.size() + r.log.landmarks.size() > 100'000'000)
      throw InputError(path, 0, "more than 1e8 messages", "split the rawlog");
  }
  if (index == 0) throw InputError(path, 0, "not an MRPT rawlog (or an empty one)", kFix);
  return std::move(r.log);
}

LaserLog ReadRawlog(const std::string& path, std::uint64_t max_bytes) {
  if (!IsRegularFile(path)) throw InputError(path, 0, "cannot open the rawlog", "check the path");
  return ParseRawlog(ReadRawlogBytes(path, max_bytes), path);
}

LaserLog ReadRawlog(const std::string& path) { return ReadRawlog(path, limits::kMaxDecompressedBytes); }

void WriteRawlog(const Stream& stream, const std::string& path, RawlogLayout layout) {
  const double origin_s = stream.header.time_origin_s.value_or(0.0);
  const auto stamp = [&](double t_s) { return ToMrptTime(origin_s + t_s); };
  const double sigma_range_m = stream.header.sensors.lidar ? stream.header.sensors.lidar->sigma_range_m : 0.0;
  mrpt::obs::CRawlog rawlog;
  SE2 pose = stream.header.start_pose;
  SE2 framed = pose;  ///< the odometry pose at the last frame (kFrames)
  const bool frames = layout == RawlogLayout::kFrames;
  // kFrames: the motion since the last frame as an action, then the observation in a frame.
  auto insert = [&](const mrpt::obs::CObservation::Ptr& o, double t_s) {
    if (!frames) {
      rawlog.insert(o);
      return;
    }
    mrpt::obs::CActionRobotMovement2D move;
    move.timestamp = stamp(t_s);
    move.computeFromOdometry(ToMrpt(framed.inverse() * pose), mrpt::obs::CActionRobotMovement2D::TMotionModelOptions());
    mrpt::obs::CActionCollection actions;
    actions.insert(move);
    rawlog.insert(actions);
    mrpt::obs::CSensoryFrame frame;
    frame.insert(o);
    rawlog.insert(frame);
    framed = pose;
  };
  auto odometry = [&](double t_s) {
    if (frames) return;
    auto o = mrpt::obs::CObservationOdometry::Create();
    o->sensorLabel = "ODOMETRY";
    o->timestamp = stamp(t_s);
    o->odometry = ToMrpt(pose);
    rawlog.insert(o);
  };
  odometry(0.0);
  for (const SensorEvent& event : stream.events) {
    if (const auto* e = std::get_if<OdometryEvent>(&event)) {
      pose = pose * e->delta;
      odometry(e->t_s);
    } else if (const auto* e = std::get_if<LaserScanEvent>(&event)) {
      auto o = mrpt::obs::CObservation2DRangeScan::Create(ToMrptScan(*e, sigma_range_m));
      o->timestamp = stamp(e->t_s);
      insert(o, e->t_s);
    } else if (const auto* e = std::get_if<LandmarkEvent>(&event)) {
      const LandmarkSensorConfig config = stream.header.sensors.landmarks.value_or(LandmarkSensorConfig{});
      auto o = mrpt::obs::CObservationBearingRange::Create(ToMrptBearingRange(*e, config));
      o->timestamp = stamp(e->t_s);
      insert(o, e->t_s);
    }
  }
  const std::filesystem::path target(path);
  if (!target.parent_path().empty()) std::filesystem::create_directories(target.parent_path());
  const std::string temporary = path + ".tmp-" + std::to_string(::getpid());
  if (!rawlog.saveToRawLogFile(temporary)) {
    std::filesystem::remove(temporary);
    throw std::runtime_error("cannot write " + path + " (MRPT's CRawlog::saveToRawLogFile failed; the file was not changed)");
  }
  std::filesystem::rename(temporary, target);
}

}  // namespace slambox::mrpt_bridge
