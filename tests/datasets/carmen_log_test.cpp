// CARMEN log conversion: beam geometry, misses, time base, the laser frame (integrated
// odometry at each scan equals that scan's laser pose), compressed files, errors with
// line numbers, and the public Intel log when present.
#include "datasets/carmen_log.hpp"

#include <bzlib.h>
#include <gtest/gtest.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "core/error.hpp"
#include "tests/support/public_data.hpp"

namespace slambox {
namespace {

std::string Flaser(int n, double range, const SE2& laser, const SE2& odom, double ts) {
  std::ostringstream s;
  s.precision(10);
  s << "FLASER " << n;
  for (int i = 0; i < n; ++i) s << " " << (i == 0 ? 81.91 : range);
  s << " " << laser.x << " " << laser.y << " " << laser.theta << " " << odom.x << " " << odom.y << " " << odom.theta
    << " " << ts << " host 0.0\n";
  return s.str();
}

std::string Odom(const SE2& p, double ts) {
  std::ostringstream s;
  s.precision(10);
  s << "ODOM " << p.x << " " << p.y << " " << p.theta << " 0 0 0 " << ts << " host 0.0\n";
  return s.str();
}

// A robot driving a quarter circle; the laser sits 0.2 m ahead of the odometry centre.
struct SyntheticLog {
  std::string text;
  std::vector<SE2> scan_laser_poses;
};

SyntheticLog MakeLog() {
  SyntheticLog log;
  const SE2 offset(0.2, 0.0, 0.0);
  log.text = "# CARMEN Logfile\nPARAM robot_front_laser_max 30.0 host 0\n";
  const double t0 = 1000000.0;
  for (int k = 0; k < 40; ++k) {
    const double a = 0.04 * k;
    const SE2 odom(3.0 * std::sin(a), 3.0 * (1 - std::cos(a)), a);
    const double ts = t0 + 0.05 * k;
    log.text += Odom(odom, ts);
    if (k % 4 == 2) {  // a scan between odometry messages, with its own odometry pose
      const SE2 mid(odom.x + 0.01, odom.y, a + 0.001);
      log.text += Flaser(180, 5.0, mid * offset, mid, ts + 0.0123);
      log.scan_laser_poses.push_back(mid * offset);
    }
  }
  return log;
}

TEST(CarmenLog, ScansInTheLaserFrameMatchTheirOdometryPoses) {
  const SyntheticLog log = MakeLog();
  const Stream s = ParseCarmenLog(log.text, "synthetic.clf");
  ASSERT_TRUE(s.header.sensors.lidar && s.header.sensors.odometry);
  EXPECT_EQ(s.header.sensors.lidar->beams, 180);
  EXPECT_DOUBLE_EQ(s.header.sensors.lidar->range_max_m, 30.0);  // from PARAM
  EXPECT_TRUE(s.groundtruth.empty());
  SE2 pose = s.header.start_pose;
  size_t scan = 0;
  double last_t = -1;
  for (const SensorEvent& e : s.events) {
    const double t = EventTime(e);
    EXPECT_GE(t, last_t);
    EXPECT_DOUBLE_EQ(t, std::round(t / s.header.dt_s) * s.header.dt_s);  // on the time grid
    last_t = t;
    if (const auto* odo = std::get_if<OdometryEvent>(&e)) pose = pose * odo->delta;
    if (const auto* l = std::get_if<LaserScanEvent>(&e)) {
      ASSERT_LT(scan, log.scan_laser_poses.size());
      const SE2& truth = log.scan_laser_poses[scan++];
      EXPECT_NEAR((pose.translation() - truth.translation()).norm(), 0.0, 1e-7) << "scan " << scan;
      EXPECT_NEAR(NormalizeAngle(pose.theta - truth.theta), 0.0, 1e-8);
      ASSERT_EQ(l->ranges_m.size(), 180u);
      EXPECT_DOUBLE_EQ(l->angle_min_rad, -M_PI / 2);            // even n: fov / n steps
      EXPECT_DOUBLE_EQ(l->angle_increment_rad, M_PI / 180);
      EXPECT_EQ(l->valid[0], 0);  // 81.91 >= range max: a miss, reported at range max
      EXPECT_DOUBLE_EQ(l->ranges_m[0], 30.0);
      EXPECT_EQ(l->valid[1], 1);
      EXPECT_DOUBLE_EQ(l->ranges_m[1], 5.0);
    }
  }
  EXPECT_EQ(scan, log.scan_laser_poses.size());
  EXPECT_DOUBLE_EQ(EventTime(s.events.front()), 0.05);  // times from the first message
}

TEST(CarmenLog, RobotLaserCarriesItsOwnGeometryAndOddFlaserEndsAtTheEdges) {
  std::string text = "ROBOTLASER1 0 -1.570796 3.141593 0.017453 81.9 0.01 0 3 1.0 2.0 90.0 0 "
                     "0.1 0 0 0 0 0 0 0 0 0 0 5.0 host 0\n";
  text += "ROBOTLASER1 0 -1.570796 3.141593 0.017453 81.9 0.01 0 3 1.0 2.0 3.0 0 "
          "0.6 0 0 0.5 0 0 0 0 0 0 0 5.5 host 0\n";
  const Stream s = ParseCarmenLog(text, "robotlaser.clf");
  const auto& scan = std::get<LaserScanEvent>(s.events.back());
  EXPECT_DOUBLE_EQ(scan.angle_min_rad, -1.570796);
  EXPECT_DOUBLE_EQ(scan.angle_increment_rad, 0.017453);
  EXPECT_DOUBLE_EQ(scan.range_max_m, 81.9);
  EXPECT_EQ(std::get<LaserScanEvent>(s.events.front()).valid[2], 0);  // 90 m > 81.9: a miss
  const auto& odo = std::get<OdometryEvent>(s.events[1]);
  EXPECT_NEAR(odo.delta.x, 0.5, 1e-12);  // the laser moved with the robot
  EXPECT_NEAR((s.header.start_pose.translation() - Eigen::Vector2d(0.1, 0)).norm(), 0, 1e-12);

  const Stream odd = ParseCarmenLog(Flaser(181, 2.0, SE2(), SE2(), 1.0), "odd.clf");
  const auto& o = std::get<LaserScanEvent>(odd.events.back());
  EXPECT_DOUBLE_EQ(o.angle_min_rad + 180 * o.angle_increment_rad, M_PI / 2);
}

void ExpectErrorAtLine(const std::string& text, int line, const std::string& words) {
  try {
    ParseCarmenLog(text, "bad.clf");
    FAIL() << "no error for: " << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "bad.clf");
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("fix:"), std::string::npos) << e.what();
  }
}

TEST(CarmenLog, BadLinesNameTheLineAndTheProblem) {
  const std::string good = Odom(SE2(), 1.0);
  ExpectErrorAtLine(good + "FLASER 3 1.0 2.0 0 0 0 0 0 0 1.5 host 0\n", 2, "expected 3 readings");
  ExpectErrorAtLine(good + "FLASER 2 1.0 abc 0 0 0 0 0 0 1.5 host 0\n", 2, "'abc'");
  ExpectErrorAtLine(good + "FLASER 2 1.0 nan 0 0 0 0 0 0 1.5 host 0\n", 2, "not a finite number");
  ExpectErrorAtLine("# c\n" + good + "ODOM 1 2 3\n", 3, "ts host logger_ts");
  ExpectErrorAtLine(good, 0, "no FLASER or ROBOTLASER1");
  ExpectErrorAtLine(good + "FLASER -4 1 host 0\n", 2, "whole count");
}

TEST(CarmenLog, CompressedFilesReadLikePlainOnesAndCorruptOnesFail) {
  const SyntheticLog log = MakeLog();
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "slambox_carmen_test";
  std::filesystem::create_directories(dir);
  const std::string plain = (dir / "log.clf").string(), gz = (dir / "log.clf.gz").string(),
                    bz = (dir / "log.clf.bz2").string(), broken = (dir / "broken.clf.bz2").string();
  std::ofstream(plain) << log.text;
  gzFile g = gzopen(gz.c_str(), "wb");
  gzwrite(g, log.text.data(), static_cast<unsigned>(log.text.size()));
  gzclose(g);
  std::string packed(log.text.size() + 1024, '\0');
  unsigned packed_size = static_cast<unsigned>(packed.size());
  ASSERT_EQ(BZ2_bzBuffToBuffCompress(packed.data(), &packed_size, const_cast<char*>(log.text.data()),
                                     static_cast<unsigned>(log.text.size()), 9, 0, 0),
            BZ_OK);
  packed.resize(packed_size);
  std::ofstream(bz, std::ios::binary) << packed << packed;  // two concatenated streams, as pbzip2 writes
  std::ofstream(broken, std::ios::binary) << packed.substr(0, packed.size() / 2);
  const Stream a = ReadCarmenLog(plain), b = ReadCarmenLog(gz);
  EXPECT_EQ(a.events.size(), b.events.size());
  EXPECT_EQ(ReadCarmenLog(bz).events.size(), ParseCarmenLog(log.text + log.text, "twice").events.size());
  EXPECT_THROW(ReadCarmenLog(broken), InputError);
  std::ifstream gz_in(gz, std::ios::binary);
  const std::string gz_bytes((std::istreambuf_iterator<char>(gz_in)), std::istreambuf_iterator<char>());
  const std::string gz_broken = (dir / "broken.clf.gz").string();
  std::ofstream(gz_broken, std::ios::binary) << gz_bytes.substr(0, gz_bytes.size() / 2);
  EXPECT_THROW(ReadCarmenLog(gz_broken), InputError);
  EXPECT_THROW(ReadCarmenLog((dir / "missing.clf").string()), InputError);
  std::filesystem::remove_all(dir);
}

TEST(CarmenLog, TimeOriginMapsLogTimesOntoStreamTimes) {
  // Messages out of file order at odd microseconds: the origin is the earliest ipc time,
  // and every event's log time t_s + origin is within dt/2 of the message's own.
  // Timestamps in microseconds as CARMEN writes them (the helpers above keep 10 digits).
  const double t0 = 976052905.167303;
  const auto at = [](std::string line, double ts) {
    std::ostringstream s;
    s.setf(std::ios::fixed);
    s.precision(7);
    s << ts;
    const auto mark = line.rfind(" host");
    const auto start = line.rfind(' ', mark - 1);
    return line.substr(0, start + 1) + s.str() + line.substr(mark);
  };
  std::string text = at(Odom(SE2(0.1, 0, 0), 1.0), t0 + 0.1004) + at(Odom(SE2(0, 0, 0), 1.0), t0) +
                     at(Flaser(181, 2.0, SE2(0.3, 0, 0), SE2(0.1, 0, 0), 1.0), t0 + 0.1234567) +
                     at(Odom(SE2(0.2, 0, 0), 1.0), t0 + 0.2999);
  const Stream s = ParseCarmenLog(text, "tiny.clf");
  ASSERT_TRUE(s.header.time_origin_s.has_value());
  EXPECT_EQ(*s.header.time_origin_s, t0);
  // odometry, the scan's own odometry pose, the scan, odometry (the message at t0 moved the start)
  const double expected[] = {0.100, 0.123, 0.123, 0.300};
  const double ipc[] = {t0 + 0.1004, t0 + 0.1234567, t0 + 0.1234567, t0 + 0.2999};
  ASSERT_EQ(s.events.size(), 4u);
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(EventTime(s.events[i]), expected[i], 1e-12);
    EXPECT_LE(std::abs(EventTime(s.events[i]) + *s.header.time_origin_s - ipc[i]), 0.5 * s.header.dt_s + 1e-6);
  }
  EXPECT_TRUE(std::holds_alternative<LaserScanEvent>(s.events[2]));
}

TEST(CarmenLog, MessagesStampedBeforeTheClockStopTheImportOrAreDropped) {
  // A SLAM tool's log: after each scan the corrected pose, stamped 0 (the public intel-,
  // freiburg-079- and csail-corrected logs). Sorted by time, every such pose would land at
  // t = 0 and turn the odometry into jumps; by default the import stops at the first one.
  const SyntheticLog log = MakeLog();
  std::string stamped_zero;
  int first_zero_line = 0, line = 0, zeros = 0;
  std::istringstream in(log.text);
  for (std::string l; std::getline(in, l);) {
    stamped_zero += l + "\n";
    ++line;
    if (l.rfind("FLASER", 0) == 0) {
      stamped_zero += Odom(SE2(50.0, -20.0, 1.0), 0.0);
      ++zeros;
      if (first_zero_line == 0) first_zero_line = line + 1;
    }
  }
  ASSERT_GT(zeros, 2);
  ExpectErrorAtLine(stamped_zero, first_zero_line, "clock goes backwards");

  CarmenImportOptions drop;
  drop.out_of_order = CarmenOutOfOrder::kDrop;
  CarmenImportReport report;
  const Stream dropped = ParseCarmenLog(stamped_zero, "zeros.clf", drop, &report);
  EXPECT_EQ(report.out_of_order_dropped, zeros);
  const Stream clean = ParseCarmenLog(log.text, "clean.clf");
  ASSERT_EQ(dropped.events.size(), clean.events.size());
  for (size_t i = 0; i < clean.events.size(); ++i) EXPECT_EQ(EventTime(dropped.events[i]), EventTime(clean.events[i]));
  EXPECT_EQ(dropped.header.start_pose.vector(), clean.header.start_pose.vector());

  // Within the tolerance a message out of file order is kept and sorted (interleaved
  // processes: the public intel log has one 0.90 s behind).
  const std::string interleaved = Odom(SE2(), 10.0) + Odom(SE2(0.1, 0, 0), 12.0) + Odom(SE2(0.05, 0, 0), 11.0) +
                                  Flaser(181, 2.0, SE2(0.1, 0, 0), SE2(0.1, 0, 0), 12.5);
  CarmenImportReport none;
  EXPECT_NO_THROW(ParseCarmenLog(interleaved, "interleaved.clf", {}, &none));
  EXPECT_EQ(none.out_of_order_dropped, 0);
  ExpectErrorAtLine(Odom(SE2(), 10.0) + Odom(SE2(0.1, 0, 0), 16.0) + Odom(SE2(0.05, 0, 0), 10.9) +
                        Flaser(181, 2.0, SE2(0.1, 0, 0), SE2(0.1, 0, 0), 16.5),
                    3, "5.100 s before line 2");
}

TEST(CarmenLog, AClockTooCoarseToOrderTheScansIsRejected) {
  // csail-corrected writes its timestamps with 6 digits (1.13486e+09): 404 of its 405
  // consecutive scan pairs share one, so scans cannot be placed against the odometry.
  std::string coarse;
  for (int k = 0; k < 6; ++k)
    coarse += Odom(SE2(0.1 * k, 0, 0), 1134860000.0 + (k >= 4 ? 10000.0 : 0.0)) +
              Flaser(181, 2.0, SE2(0.1 * k, 0, 0), SE2(0.1 * k, 0, 0), 1134860000.0 + (k >= 4 ? 10000.0 : 0.0));
  ExpectErrorAtLine(coarse, 4, "4 of 5 consecutive scans share their timestamp");
  // One repeat among many is a real log's rounding, not a coarse clock.
  std::string fine;
  for (int k = 0; k < 6; ++k) fine += Flaser(181, 2.0, SE2(0.1 * k, 0, 0), SE2(0.1 * k, 0, 0), 100.0 + 0.2 * (k == 1 ? 0 : k));
  EXPECT_NO_THROW(ParseCarmenLog(fine, "fine.clf"));
}

TEST(CarmenLog, CorrectedLogsWhenPresentNeedTheirZeroStampsDropped) {
  const std::string path = testing::PublicDataFile(SLAMBOX_SOURCE_DIR, "rawlogs/intel-corrected.log.gz");
  if (path.empty()) GTEST_SKIP() << "public data absent (../shared/data or $SLAMBOX_DATA)";
  EXPECT_THROW(ReadCarmenLog(path), InputError);
  CarmenImportOptions drop;
  drop.out_of_order = CarmenOutOfOrder::kDrop;
  CarmenImportReport report;
  const Stream s = ReadCarmenLog(path, drop, &report);
  size_t scans = 0;
  for (const SensorEvent& e : s.events) scans += std::holds_alternative<LaserScanEvent>(e);
  EXPECT_EQ(scans, 910u);                     // every FLASER line (the data README)
  EXPECT_EQ(report.out_of_order_dropped, 910);  // one pose stamped 0 after each
  EXPECT_NEAR(s.header.duration_s, 2691.3, 0.1);
}

TEST(CarmenLog, IntelLabLogWhenPresent) {
  const std::string path = testing::PublicDataFile(SLAMBOX_SOURCE_DIR, "rawlogs/intel.clf.bz2");
  if (path.empty()) GTEST_SKIP() << "public data absent (../shared/data or $SLAMBOX_DATA)";
  const Stream s = ReadCarmenLog(path);
  size_t scans = 0;
  for (const SensorEvent& e : s.events) scans += std::holds_alternative<LaserScanEvent>(e);
  EXPECT_EQ(scans, 13631u);  // every FLASER line (the data README)
  EXPECT_EQ(s.header.sensors.lidar->beams, 180);
  EXPECT_NEAR(s.header.duration_s, 2691.3, 0.1);
  ASSERT_TRUE(s.header.time_origin_s.has_value());
  EXPECT_LE(*s.header.time_origin_s, 976052905.167303);  // before the first relation (data README)
}

}  // namespace
}  // namespace slambox
