#include "sim/simulate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "core/error.hpp"
#include "core/stream_io.hpp"
#include "sim/box2d_world.hpp"
#include "test_scenarios.hpp"

namespace slambox {
namespace {

using testing::RoomScenario;

std::size_t Hash(const Stream& s) { return std::hash<std::string>{}(SerializeStream(s)); }

TEST(Simulate, DrivesThePathWithoutCollision) {
  SimulationReport report;
  const Stream s = Simulate(RoomScenario(), 3, {}, &report);
  EXPECT_TRUE(report.path_completed);
  EXPECT_EQ(report.wall_contacts, 0);
  // Two laps of three sides of a 7 m x 5 m rectangle plus the side back to the start: 43 m.
  EXPECT_NEAR(report.distance_m, 43.0, 0.1);
  const SE2 end = s.groundtruth.back().pose;
  EXPECT_NEAR(end.x, 1.5, 0.03);
  EXPECT_NEAR(end.y, 6.5, 0.03);
  EXPECT_EQ(static_cast<long>(s.groundtruth.size()), report.steps + 1);
  EXPECT_DOUBLE_EQ(s.header.duration_s, report.steps * 0.01);
  // Turn-then-drive at 1 m/s and 90 deg/s: at least 48 s + 7 turns of 90 deg.
  EXPECT_GT(s.header.duration_s, 43.0 + 7.0);
  EXPECT_LT(s.header.duration_s, 90.0);
}

TEST(Simulate, EventTimesAreStepMultiplesInSensorOrder) {
  Scenario sc = RoomScenario();
  sc.duration_s = 3.0;
  const Stream s = Simulate(sc, 1);
  const double dt = s.header.dt_s;
  for (size_t i = 0; i < s.groundtruth.size(); ++i) ASSERT_EQ(s.groundtruth[i].t_s, static_cast<double>(i) * dt);
  int odometry = 0, scans = 0, landmarks = 0, gyro = 0;
  double last_t = -1.0;
  int last_rank = -1;
  for (const SensorEvent& e : s.events) {
    const double t = EventTime(e);
    const long k = std::lround(t / dt);
    ASSERT_EQ(t, static_cast<double>(k) * dt);
    const int rank = static_cast<int>(e.index());  // odometry 0, laser 1, landmarks 2, gyro 3
    const int order = rank == 3 ? 1 : rank == 0 ? 0 : rank + 1;  // odometry, gyro, lidar, landmarks
    if (t == last_t) {
      ASSERT_GT(order, last_rank);
    } else {
      ASSERT_GT(t, last_t);
    }
    last_t = t;
    last_rank = order;
    odometry += rank == 0;
    scans += rank == 1;
    landmarks += rank == 2;
    gyro += rank == 3;
  }
  EXPECT_EQ(s.header.duration_s, 3.0);
  EXPECT_EQ(odometry, 150);  // 50 Hz, none at t = 0
  EXPECT_EQ(gyro, 151);      // 50 Hz from t = 0
  EXPECT_EQ(scans, 31);      // 10 Hz from t = 0
  EXPECT_EQ(landmarks, 31);
}

TEST(Simulate, SameSeedIsBitIdenticalOtherSeedDiffers) {
  Scenario sc = RoomScenario();
  sc.duration_s = 5.0;
  const std::size_t a = Hash(Simulate(sc, 42)), b = Hash(Simulate(sc, 42)), c = Hash(Simulate(sc, 43));
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

/// FNV-1a 64 of the serialized header, events and ground truth (the header's version and
/// YAML text are left out: they change with releases and formatting, not with the
/// simulation; so are the file format's version field and checksum, bytes 8-11 and the last 8).
std::uint64_t GoldenHash(Stream s) {
  s.header.slambox_version.clear();
  s.header.scenario_yaml.clear();
  const std::string bytes = SerializeStream(s);
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (std::size_t i = 0; i + 8 < bytes.size(); ++i)
    if (i < 8 || i >= 12) h = (h ^ static_cast<unsigned char>(bytes[i])) * 0x100000001b3ull;
  return h;
}

TEST(Simulate, GoldenHashOfAShortRun) {
  Scenario sc = RoomScenario();
  sc.duration_s = 2.0;
  sc.sensors.lidar->sigma_bearing_deg = 0.2;
  sc.sensors.lidar->dropout_prob = 0.05;
  sc.sensors.landmarks->clutter_per_scan = 1.0;
  // A deliberate change of the simulator's output updates this value; anything else is a bug.
  // Last change: the header's landmark sensor gained detection_prob_known (the events are
  // unchanged: `slambox export` of `landmarks` seed 7 with clutter 1, before and after, diffs empty).
  EXPECT_EQ(GoldenHash(Simulate(sc, 7)), 12758479581751757991ull) << std::hex << GoldenHash(Simulate(sc, 7));
}

TEST(Simulate, DurationExtendsPastThePathAndTheRobotWaits) {
  Scenario sc = RoomScenario();
  sc.robot.laps = 1;
  sc.duration_s = 60.0;
  SimulationReport report;
  const Stream s = Simulate(sc, 0, {}, &report);
  EXPECT_TRUE(report.path_completed);
  EXPECT_EQ(s.header.duration_s, 60.0);
  EXPECT_NEAR(s.groundtruth.back().pose.y, 6.5, 0.03);
}

TEST(Simulate, KidnapTeleportsTruthButNotOdometry) {
  Scenario sc = RoomScenario();
  sc.robot.kidnap = KidnapSpec{2.0, {8.5, 6.5, 90.0}};
  sc.duration_s = 2.5;
  const Stream s = Simulate(sc, 0);
  const SE2 after = s.groundtruth[200].pose;  // t = 2.0: just teleported
  EXPECT_NEAR(after.x, 8.5, 1e-5);
  EXPECT_NEAR(after.y, 6.5, 1e-5);
  // Odometry between t = 1.98 and 2.0 shows a wheel motion of millimetres, not the jump.
  for (const SensorEvent& e : s.events)
    if (const auto* o = std::get_if<OdometryEvent>(&e); o && o->t_s == 2.0) {
      EXPECT_LT(o->delta.translation().norm(), 0.05);
    }
}

TEST(Simulate, UnreachableWaypointIsAnInputErrorNamingIt) {
  Scenario sc = RoomScenario();
  sc.robot.path = {{1.5, 1.5}, {5.0, 4.0}};  // the centre of the pillar
  try {
    Simulate(sc, 0);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("waypoint 1 [5, 4]"), std::string::npos) << e.what();
  }
}

TEST(Movers, WalkTheirPathBackAndForthOrStop) {
  MoverSpec m;
  m.path = {{0, 0}, {3, 0}, {3, 4}};  // 7 m long
  m.speed_mps = 2.0;
  EXPECT_NEAR((MoverPositionAt(m, 1.0) - Eigen::Vector2d(2, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((MoverPositionAt(m, 2.5) - Eigen::Vector2d(3, 2)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((MoverPositionAt(m, 4.5) - Eigen::Vector2d(3, 2)).norm(), 0.0, 1e-12);  // 9 m: 2 m on the way back
  EXPECT_NEAR((MoverPositionAt(m, 7.0) - Eigen::Vector2d(0, 0)).norm(), 0.0, 1e-12);  // back at the start
  m.loop = false;
  EXPECT_NEAR((MoverPositionAt(m, 4.5) - Eigen::Vector2d(3, 4)).norm(), 0.0, 1e-12);  // stays at the end
}

TEST(Movers, KinematicBodiesFollowTheirPaths) {
  Scenario sc = RoomScenario();
  MoverSpec cart;
  cart.is_box = true;
  cart.path = {{2, 3}, {8, 3}};
  cart.speed_mps = 0.5;
  sc.movers = {cart};
  sc.robot.path = {{1.5, 1.5}};
  const World world = MakeWorld(sc);
  PhysicsWorld physics(sc, world);
  for (int k = 1; k <= 400; ++k) physics.Step(0.01, k * 0.01);
  const std::vector<MoverShape> movers = physics.Movers();
  ASSERT_EQ(movers.size(), 1u);
  EXPECT_NEAR(movers[0].T_world_mover.x, 4.0, 1e-4);
  EXPECT_NEAR(movers[0].T_world_mover.y, 3.0, 1e-4);
  EXPECT_TRUE(movers[0].is_box);
}

}  // namespace
}  // namespace slambox
