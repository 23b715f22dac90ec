// MRPT rawlogs in and out (slam/mrpt/mrpt_rawlog.hpp through the MRPT plugin,
// app/rawlog_format.hpp; assembled like CARMEN logs by datasets/laser_log.hpp):
// a simulated stream round-trips through MRPT's CRawlog writer and reader; the MRPT
// versions of the public CARMEN logs (../shared/data/rawlogs/mrpt/) convert to the same
// scans and odometry as `slambox convert carmen` of the same log.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include "app/rawlog_format.hpp"
#include "core/error.hpp"
#include "core/stream_io.hpp"
#include "datasets/carmen_log.hpp"
#include "datasets/laser_log.hpp"
#include "sim/simulate.hpp"
#include "tests/support/public_data.hpp"
#include "tests/support/slambox_cli.hpp"

namespace slambox {
namespace {

namespace fs = std::filesystem;
using namespace slambox::testing;

// MRPT stores ranges and bearings as floats: a double comes back within half a float ulp.
double FloatError(double v) { return std::abs(v) * 6e-8 + 1e-30; }

Stream RoundTrip(const Stream& s, const fs::path& file) {
  RawlogFormat().write(s, file.string(), RawlogLayout::kObservations);
  LaserLogOptions o;
  o.dt_s = s.header.dt_s;
  if (s.header.sensors.lidar) o.range_min_m = s.header.sensors.lidar->range_min_m, o.range_max_m = s.header.sensors.lidar->range_max_m;
  return AssembleLaserLog(RawlogFormat().read(file.string()), file.string(), o);
}

void ExpectSameEvents(const Stream& a, const Stream& b) {
  ASSERT_EQ(a.events.size(), b.events.size());
  EXPECT_EQ(b.header.time_origin_s.value_or(-1), 0.0);
  EXPECT_NEAR(a.header.start_pose.x, b.header.start_pose.x, 1e-12);
  EXPECT_NEAR(a.header.start_pose.theta, b.header.start_pose.theta, 1e-12);
  for (std::size_t i = 0; i < a.events.size(); ++i) {
    ASSERT_EQ(a.events[i].index(), b.events[i].index()) << "event " << i;
    ASSERT_EQ(EventTime(a.events[i]), EventTime(b.events[i])) << "event " << i;  // exact: 100 ns ticks, dt steps
    if (const auto* x = std::get_if<OdometryEvent>(&a.events[i])) {
      const auto& y = std::get<OdometryEvent>(b.events[i]);
      EXPECT_NEAR(x->delta.x, y.delta.x, 1e-9) << i;  // integrated, then differenced
      EXPECT_NEAR(x->delta.y, y.delta.y, 1e-9) << i;
      EXPECT_NEAR(x->delta.theta, y.delta.theta, 1e-9) << i;
    } else if (const auto* x = std::get_if<LaserScanEvent>(&a.events[i])) {
      const auto& y = std::get<LaserScanEvent>(b.events[i]);
      ASSERT_EQ(x->ranges_m.size(), y.ranges_m.size());
      EXPECT_NEAR(x->angle_min_rad, y.angle_min_rad, 1e-6);  // MRPT's float aperture
      EXPECT_NEAR(x->angle_increment_rad, y.angle_increment_rad, 1e-8);
      EXPECT_EQ(x->valid, y.valid) << i;
      for (std::size_t k = 0; k < x->ranges_m.size(); ++k)
        if (x->valid[k]) EXPECT_NEAR(x->ranges_m[k], y.ranges_m[k], FloatError(x->ranges_m[k])) << i << " " << k;
    } else if (const auto* x = std::get_if<LandmarkEvent>(&a.events[i])) {
      const auto& y = std::get<LandmarkEvent>(b.events[i]);
      ASSERT_EQ(x->observations.size(), y.observations.size());
      for (std::size_t k = 0; k < x->observations.size(); ++k) {
        EXPECT_NEAR(x->observations[k].range_m, y.observations[k].range_m, FloatError(x->observations[k].range_m));
        EXPECT_NEAR(x->observations[k].bearing_rad, y.observations[k].bearing_rad, FloatError(M_PI));
        EXPECT_EQ(x->observations[k].id, y.observations[k].id);
      }
    }
  }
}

TEST(Rawlog, SimulatedStreamsRoundTripThroughMrptsReader) {
  const fs::path dir = FreshTempDir("rawlog");
  // loop: odometry + LIDAR; landmarks with unknown ids and clutter: odometry + range-bearing.
  const Stream loop = Simulate(LoadScenario("loop", {"duration_s=20"}), 4);
  ExpectSameEvents(loop, RoundTrip(loop, dir / "loop.rawlog"));
  const Stream posts = Simulate(LoadScenario("landmarks", {"duration_s=20", "sensors.landmarks.known_ids=false",
                                                           "sensors.landmarks.clutter_per_scan=1"}), 4);
  const Stream back = RoundTrip(posts, dir / "posts.rawlog");
  ExpectSameEvents(posts, back);
  ASSERT_TRUE(back.header.sensors.landmarks.has_value());
  EXPECT_FALSE(back.header.sensors.landmarks->known_ids);
  EXPECT_NEAR(back.header.sensors.landmarks->sigma_range_m, posts.header.sensors.landmarks->sigma_range_m, 1e-7);
  EXPECT_NEAR(back.header.sensors.landmarks->range_max_m, posts.header.sensors.landmarks->range_max_m, 1e-5);
  EXPECT_FALSE(fs::exists(dir / ("posts.rawlog.tmp-" + std::to_string(::getpid()))));
}

TEST(Rawlog, FramesLayoutCarriesTheOdometryBetweenObservations) {
  // --rawlog-layout frames (what MRPT's kf-slam and rbpf-slam apps read): before each
  // observation an action with the odometry increment since the previous one.
  const fs::path dir = FreshTempDir("rawlog_frames");
  Scenario sc = LoadScenario("landmarks");
  sc.duration_s = 6.0;
  const Stream s = Simulate(sc, 3);
  RawlogFormat().write(s, (dir / "f.rawlog").string(), RawlogLayout::kFrames);
  const LaserLog log = RawlogFormat().read((dir / "f.rawlog").string());
  std::vector<SE2> odometry_at;  // the stream's integrated odometry at each landmark event
  std::vector<const LandmarkEvent*> events;
  SE2 pose = s.header.start_pose;
  for (const SensorEvent& e : s.events) {
    if (const auto* o = std::get_if<OdometryEvent>(&e)) pose = pose * o->delta;
    if (const auto* l = std::get_if<LandmarkEvent>(&e)) odometry_at.push_back(pose), events.push_back(l);
  }
  ASSERT_GT(events.size(), 20u);
  ASSERT_EQ(log.landmarks.size(), events.size());
  ASSERT_EQ(log.odometry.size(), events.size() + 1);  // the reader's origin, then one pose per action
  EXPECT_TRUE(log.scans.empty());
  for (std::size_t k = 0; k < events.size(); ++k) {
    const SE2 expected = s.header.start_pose.inverse() * odometry_at[k];
    const SE2& got = log.odometry[k + 1].pose;
    EXPECT_NEAR(got.x, expected.x, 1e-9) << k;
    EXPECT_NEAR(got.y, expected.y, 1e-9) << k;
    EXPECT_NEAR(std::remainder(got.theta - expected.theta, 2 * M_PI), 0.0, 1e-9) << k;
    EXPECT_NEAR(log.landmarks[k].ts, events[k]->t_s, 1e-6) << k;
    ASSERT_EQ(log.landmarks[k].observations.size(), events[k]->observations.size()) << k;
    for (std::size_t i = 0; i < events[k]->observations.size(); ++i)
      EXPECT_EQ(log.landmarks[k].observations[i].id, events[k]->observations[i].id);
  }
}

TEST(Rawlog, CliExportThenConvertGivesTheStreamBack) {
  const fs::path dir = FreshTempDir("rawlog_cli");
  const std::string b = SLAMBOX_BINARY;
  ASSERT_EQ(RunSlambox(b, "simulate loop --seed 2 --set duration_s=10 -o " + (dir / "s.stream").string()).code, 0);
  const CliResult e = RunSlambox(b, "export " + (dir / "s.stream").string() + " --format rawlog -o " + (dir / "s.rawlog").string());
  ASSERT_EQ(e.code, 0) << e.output;
  const CliResult c = RunSlambox(b, "convert rawlog " + (dir / "s.rawlog").string() + " --range-max-m 30 -o " + (dir / "back.stream").string());
  ASSERT_EQ(c.code, 0) << c.output;
  EXPECT_NE(c.output.find("scans (360 beams"), std::string::npos) << c.output;
  Stream original = ReadStream((dir / "s.stream").string());
  ExpectSameEvents(original, ReadStream((dir / "back.stream").string()));
  // A file that is not a rawlog: one message naming it, non-zero exit, no stream written.
  std::ofstream(dir / "text.rawlog") << "not a rawlog\n";
  const CliResult bad = RunSlambox(b, "convert rawlog " + (dir / "text.rawlog").string() + " -o " + (dir / "x.stream").string());
  EXPECT_NE(bad.code, 0);
  EXPECT_NE(bad.output.find((dir / "text.rawlog").string()), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(dir / "x.stream"));
}

// Integrated odometry at each scan (the stream's robot frame).
std::vector<SE2> OdometryAtScans(const Stream& s) {
  std::vector<SE2> out;
  SE2 pose = s.header.start_pose;
  for (const SensorEvent& e : s.events) {
    if (const auto* o = std::get_if<OdometryEvent>(&e)) pose = pose * o->delta;
    if (std::holds_alternative<LaserScanEvent>(e)) out.push_back(pose);
  }
  return out;
}

std::vector<const LaserScanEvent*> Scans(const Stream& s) {
  std::vector<const LaserScanEvent*> out;
  for (const SensorEvent& e : s.events)
    if (const auto* x = std::get_if<LaserScanEvent>(&e)) out.push_back(x);
  return out;
}

struct PublicLog {
  const char* carmen;
  const char* rawlog;
};

class RawlogAgreesWithCarmen : public ::testing::TestWithParam<PublicLog> {};

TEST_P(RawlogAgreesWithCarmen, SameScansAndOdometry) {
  const std::string carmen_path = PublicDataFile(SLAMBOX_SOURCE_DIR, std::string("rawlogs/") + GetParam().carmen);
  const std::string rawlog_path = PublicDataFile(SLAMBOX_SOURCE_DIR, std::string("rawlogs/mrpt/") + GetParam().rawlog);
  if (carmen_path.empty() || rawlog_path.empty()) GTEST_SKIP() << "public data not found (../shared/data or $SLAMBOX_DATA)";
  const Stream carmen = ReadCarmenLog(carmen_path);
  LaserLogOptions o;
  o.range_max_m = carmen.header.sensors.lidar->range_max_m;  // intel's CARMEN log states none (80 m), its rawlog 81 m
  const Stream rawlog = AssembleLaserLog(RawlogFormat().read(rawlog_path), rawlog_path, o);
  const auto a = Scans(carmen), b = Scans(rawlog);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_NEAR(carmen.header.start_pose.x, rawlog.header.start_pose.x, 1e-9);
  EXPECT_NEAR(carmen.header.start_pose.y, rawlog.header.start_pose.y, 1e-9);
  EXPECT_NEAR(carmen.header.start_pose.theta, rawlog.header.start_pose.theta, 1e-9);
  const std::vector<SE2> pa = OdometryAtScans(carmen), pb = OdometryAtScans(rawlog);
  EXPECT_LT((pa.back().translation() - pb.back().translation()).norm(), 1e-6);
  if (std::string(GetParam().rawlog) == "intel.rawlog") {
    // intel's CARMEN log has 631 FLASER lines out of time order; the CARMEN reader sorts
    // them by time, the rawlog (re-timed at 0.2-0.3 s steps by its converter) keeps file
    // order. The scans are the same multiset: compare them sorted by their ranges.
    auto key = [](const LaserScanEvent* s) {
      std::vector<long> k;
      for (double r : s->ranges_m) k.push_back(std::lround(r * 1000));
      return k;
    };
    std::vector<std::vector<long>> ka, kb;
    for (const auto* s : a) ka.push_back(key(s));
    for (const auto* s : b) kb.push_back(key(s));
    std::sort(ka.begin(), ka.end());
    std::sort(kb.begin(), kb.end());
    EXPECT_TRUE(ka == kb) << "the rawlog's scans are not the CARMEN log's";
    return;
  }
  double worst_range = 0, worst_pose = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i]->valid, b[i]->valid) << "scan " << i;
    for (std::size_t k = 0; k < a[i]->ranges_m.size(); ++k) worst_range = std::max(worst_range, std::abs(a[i]->ranges_m[k] - b[i]->ranges_m[k]));
    worst_pose = std::max(worst_pose, (pa[i].translation() - pb[i].translation()).norm());
    EXPECT_NEAR(a[i]->angle_min_rad, b[i]->angle_min_rad, 1e-5) << "scan " << i;
  }
  std::printf("%s: %zu scans, worst range difference %.3g m, worst odometry difference at a scan %.3g m\n",
              GetParam().rawlog, a.size(), worst_range, worst_pose);
  EXPECT_LT(worst_range, 1e-5);  // the log's centimetres through MRPT's floats
  EXPECT_LT(worst_pose, 1e-9);
  // Beam spacing: CARMEN's reader spreads an even beam count over fov/n, MRPT over aperture/(n-1).
  const double n = static_cast<double>(a.front()->ranges_m.size());
  EXPECT_NEAR(b.front()->angle_increment_rad * (n - 1), a.front()->angle_increment_rad * n, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(PublicLogs, RawlogAgreesWithCarmen,
                         ::testing::Values(PublicLog{"fr079.clf.bz2", "fr079.rawlog"}, PublicLog{"intel.clf.bz2", "intel.rawlog"}),
                         [](const auto& info) { return std::string(info.param.rawlog).substr(0, 5); });

}  // namespace
}  // namespace slambox
