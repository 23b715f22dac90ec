#include "slam/mrpt/mrpt_rawlog.hpp"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3D.h>
#include <stdexcept>

#include "core/error.hpp"
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

}  // namespace

LaserLog ReadRawlog(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw InputError(path, 0, "cannot open the rawlog", "check the path");
  mrpt::obs::CRawlog rawlog;
  bool loaded = false;
  try {
    loaded = rawlog.loadFromRawLogFile(path);
  } catch (const std::exception& e) {
    throw InputError(path, 0, std::string("MRPT cannot read it: ") + e.what(), kFix);
  }
  if (!loaded || rawlog.empty()) throw InputError(path, 0, "not an MRPT rawlog (or an empty one)", kFix);
  Reader r{path, {}, {}, false, {}};
  r.log.format = "MRPT rawlog";
  for (std::size_t i = 0; i < rawlog.size(); ++i) {
    switch (rawlog.getType(i)) {
      case mrpt::obs::CRawlog::etObservation: r.Observation(*rawlog.getAsObservation(i), i); break;
      case mrpt::obs::CRawlog::etSensoryFrame:
        for (const auto& o : *rawlog.getAsObservations(i)) r.Observation(*o, i);
        break;
      case mrpt::obs::CRawlog::etActionCollection: r.Action(*rawlog.getAsAction(i), i); break;
      default: break;
    }
    if (r.log.scans.size() + r.log.odometry.size() + r.log.landmarks.size() > 100'000'000)
      throw InputError(path, 0, "more than 1e8 messages", "split the rawlog");
  }
  return std::move(r.log);
}

void WriteRawlog(const Stream& stream, const std::string& path) {
  const double origin_s = stream.header.time_origin_s.value_or(0.0);
  const auto stamp = [&](double t_s) { return ToMrptTime(origin_s + t_s); };
  const double sigma_range_m = stream.header.sensors.lidar ? stream.header.sensors.lidar->sigma_range_m : 0.0;
  mrpt::obs::CRawlog rawlog;
  SE2 pose = stream.header.start_pose;
  auto odometry = [&](double t_s) {
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
      rawlog.insert(o);
    } else if (const auto* e = std::get_if<LandmarkEvent>(&event)) {
      const LandmarkSensorConfig config = stream.header.sensors.landmarks.value_or(LandmarkSensorConfig{});
      auto o = mrpt::obs::CObservationBearingRange::Create(ToMrptBearingRange(*e, config));
      o->timestamp = stamp(e->t_s);
      rawlog.insert(o);
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
