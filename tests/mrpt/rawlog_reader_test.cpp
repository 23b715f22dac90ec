// The MRPT rawlog reader (slam/mrpt/mrpt_rawlog.hpp) on the actions / sensory-frames layout
// (what MRPT's kf-slam and rbpf-slam datasets use), written here with MRPT's own classes:
// odometry increments composed into poses, a laser mounted off the robot's origin, and a
// range-bearing sensor whose pose moves its observations to the robot origin.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3D.h>

#include <fstream>
#include <iterator>
#include <zlib.h>

#include "core/error.hpp"
#include "slam/mrpt/mrpt_convert.hpp"
#include "slam/mrpt/mrpt_rawlog.hpp"

namespace slambox {
namespace {

namespace fs = std::filesystem;

TEST(RawlogReader, SensoryFrameLayoutWithMountedSensors) {
  const fs::path file = fs::temp_directory_path() / ("slambox_sf_" + std::to_string(::getpid()) + ".rawlog");
  const SE2 step(1.0, 0.2, 0.1);  // the odometry increment between frames
  mrpt::obs::CRawlog rawlog;
  for (int k = 0; k < 5; ++k) {
    mrpt::obs::CActionRobotMovement2D move;
    move.timestamp = mrpt::Clock::fromDouble(100.0 + k);
    move.computeFromOdometry(mrpt_bridge::ToMrpt(step), mrpt::obs::CActionRobotMovement2D::TMotionModelOptions());
    mrpt::obs::CActionCollection actions;
    actions.insert(move);
    rawlog.insert(actions);
    mrpt::obs::CSensoryFrame frame;
    auto scan = mrpt::obs::CObservation2DRangeScan::Create();
    scan->timestamp = mrpt::Clock::fromDouble(100.5 + k);
    scan->sensorPose = mrpt::poses::CPose3D(0.2, 0.0, 0.0, 0.0, 0.0, 0.0);
    scan->aperture = static_cast<float>(M_PI);
    scan->rightToLeft = true;
    scan->maxRange = 30.0f;
    scan->resizeScan(5);
    for (int i = 0; i < 5; ++i) {
      scan->setScanRange(i, 1.0f + 0.5f * static_cast<float>(i + k));
      scan->setScanRangeValidity(i, i != 2);
    }
    frame.insert(scan);
    auto posts = mrpt::obs::CObservationBearingRange::Create();
    posts->timestamp = mrpt::Clock::fromDouble(100.5 + k);
    posts->setSensorPose(mrpt::poses::CPose3D(0.1, 0.05, 0.0, 0.2, 0.0, 0.0));
    posts->sensor_std_range = 0.05f;
    posts->maxSensorDistance = 12.0f;
    mrpt::obs::CObservationBearingRange::TMeasurement m;
    m.range = 2.0f;
    m.yaw = 0.3f;
    m.pitch = 0.0f;
    m.landmarkID = 7;
    posts->sensedData.push_back(m);
    frame.insert(posts);
    rawlog.insert(frame);
  }
  ASSERT_TRUE(rawlog.saveToRawLogFile(file.string()));
  const LaserLog log = mrpt_bridge::ReadRawlog(file.string());
  fs::remove(file);

  EXPECT_EQ(log.format, "MRPT rawlog");
  ASSERT_EQ(log.odometry.size(), 6u);  // the origin at the first action, then one pose per action
  SE2 expected;
  for (std::size_t k = 0; k < log.odometry.size(); ++k) {
    EXPECT_NEAR(log.odometry[k].pose.x, expected.x, 1e-9) << k;
    EXPECT_NEAR(log.odometry[k].pose.y, expected.y, 1e-9) << k;
    EXPECT_NEAR(log.odometry[k].pose.theta, expected.theta, 1e-9) << k;
    EXPECT_NEAR(log.odometry[k].ts, 100.0 + std::max<double>(0, double(k) - 1), 1e-6) << k;
    expected = expected * step;
  }
  ASSERT_EQ(log.scans.size(), 5u);
  EXPECT_NEAR(log.T_robot_laser.x, 0.2, 1e-12);
  EXPECT_EQ(log.T_robot_laser.y, 0.0);
  const LaserLog::Scan& s = log.scans[3];
  EXPECT_NEAR(s.ts, 103.5, 1e-6);
  EXPECT_NEAR(s.angle_min_rad, -M_PI / 2, 1e-6);
  EXPECT_NEAR(s.angle_increment_rad, M_PI / 4, 1e-6);  // MRPT: aperture / (N - 1)
  EXPECT_EQ(s.valid, (std::vector<std::uint8_t>{1, 1, 0, 1, 1}));
  EXPECT_NEAR(s.ranges_m[4], 1.0 + 0.5 * 7, 1e-6);
  EXPECT_EQ(s.range_max_m, 30.0);
  ASSERT_EQ(log.landmarks.size(), 5u);
  ASSERT_EQ(log.landmarks[0].observations.size(), 1u);
  const LandmarkObservation& o = log.landmarks[0].observations[0];
  const Eigen::Vector2d p = SE2(0.1, 0.05, 0.2) * Eigen::Vector2d(2.0 * std::cos(0.3f), 2.0 * std::sin(0.3f));
  EXPECT_NEAR(o.range_m, p.norm(), 1e-6);
  EXPECT_NEAR(o.bearing_rad, std::atan2(p.y(), p.x()), 1e-6);
  EXPECT_EQ(o.id, 7);
  ASSERT_TRUE(log.landmark_sensor.has_value());
  EXPECT_TRUE(log.landmark_sensor->known_ids);
  EXPECT_FALSE(log.landmark_sensor->detection_prob_known);  // CObservationBearingRange does not carry it
  EXPECT_NEAR(log.landmark_sensor->sigma_range_m, 0.05, 1e-7);
  EXPECT_NEAR(log.landmark_sensor->range_max_m, 12.0, 1e-6);
}

TEST(RawlogReader, RefusesWhatIsNotARawlog) {
  const fs::path file = fs::temp_directory_path() / ("slambox_bad_" + std::to_string(::getpid()) + ".rawlog");
  std::FILE* f = std::fopen(file.c_str(), "w");
  std::fputs("ODOM 0 0 0 0 0 0 1 nohost 0\n", f);  // a CARMEN line, not MRPT serialization
  std::fclose(f);
  for (const std::string& path : {file.string(), file.string() + ".missing"}) {
    try {
      mrpt_bridge::ReadRawlog(path);
      ADD_FAILURE() << "accepted " << path;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  }
  fs::remove(file);
}

/// A small observations-layout rawlog (MRPT's saveToRawLogFile writes it gzip-compressed).
fs::path WriteScansRawlog(const std::string& tag, int scans) {
  const fs::path file = fs::temp_directory_path() / ("slambox_" + tag + "_" + std::to_string(::getpid()) + ".rawlog");
  mrpt::obs::CRawlog rawlog;
  for (int k = 0; k < scans; ++k) {
    auto scan = mrpt::obs::CObservation2DRangeScan::Create();
    scan->timestamp = mrpt::Clock::fromDouble(10.0 + k);
    scan->aperture = static_cast<float>(M_PI);
    scan->maxRange = 30.0f;
    scan->resizeScan(181);
    for (int i = 0; i < 181; ++i) {
      scan->setScanRange(i, 2.0f);
      scan->setScanRangeValidity(i, true);
    }
    rawlog.insert(scan);
  }
  EXPECT_TRUE(rawlog.saveToRawLogFile(file.string()));
  return file;
}

std::string Gunzip(const fs::path& file) {
  gzFile f = gzopen(file.c_str(), "rb");
  std::string out;
  char buffer[4096];
  for (int got; (got = gzread(f, buffer, sizeof buffer)) > 0;) out.append(buffer, static_cast<std::size_t>(got));
  gzclose(f);
  return out;
}

void WriteBytes(const fs::path& file, const std::string& bytes) { std::ofstream(file, std::ios::binary) << bytes; }

std::string ErrorOf(const std::string& path, std::uint64_t max_bytes) {
  try {
    mrpt_bridge::ReadRawlog(path, max_bytes);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(RawlogReader, PlainAndCompressedReadTheSame) {
  const fs::path gz = WriteScansRawlog("gz", 4);
  const fs::path plain = gz.string() + ".plain";
  WriteBytes(plain, Gunzip(gz));
  const LaserLog a = mrpt_bridge::ReadRawlog(gz.string()), b = mrpt_bridge::ReadRawlog(plain.string());
  ASSERT_EQ(a.scans.size(), 4u);
  ASSERT_EQ(b.scans.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(a.scans[k].ts, b.scans[k].ts);
    EXPECT_EQ(a.scans[k].ranges_m, b.scans[k].ranges_m);
  }
  fs::remove(gz);
  fs::remove(plain);
}

TEST(RawlogReader, ContentOverTheLimitIsRefusedWhileReading) {
  const fs::path gz = WriteScansRawlog("limit", 20);
  const std::uint64_t size = Gunzip(gz).size();
  const std::string refused = ErrorOf(gz.string(), size - 1);
  EXPECT_NE(refused.find(gz.string()), std::string::npos) << refused;
  EXPECT_NE(refused.find("more than " + std::to_string(size - 1) + " bytes"), std::string::npos) << refused;
  EXPECT_EQ(ErrorOf(gz.string(), size), "");  // exactly at the limit: read whole
  fs::remove(gz);
}

TEST(RawlogReader, TruncatedFilesAreRefusedNamingTheObject) {
  const fs::path gz = WriteScansRawlog("cut", 3);
  const std::string bytes = Gunzip(gz);
  const fs::path plain = gz.string() + ".plain";
  WriteBytes(plain, bytes.substr(0, bytes.size() - 10));  // the third scan loses its end
  const std::string cut = ErrorOf(plain.string(), 1u << 30);
  EXPECT_NE(cut.find(plain.string()), std::string::npos) << cut;
  EXPECT_NE(cut.find("object 2"), std::string::npos) << cut;
  // A gzip stream cut short is corrupt compressed data, not a shorter log.
  std::ifstream in(gz, std::ios::binary);
  const std::string compressed((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  WriteBytes(plain, compressed.substr(0, compressed.size() / 2));
  const std::string corrupt = ErrorOf(plain.string(), 1u << 30);
  EXPECT_NE(corrupt.find(plain.string()), std::string::npos) << corrupt;
  EXPECT_FALSE(corrupt.empty());
  fs::remove(gz);
  fs::remove(plain);
}

}  // namespace
}  // namespace slambox
