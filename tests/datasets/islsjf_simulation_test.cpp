// The 2D-I-SLSJF simulation folder (sensor_data, speed, turn rate, parameters, ground truth)
// into a stream: the motion step and its covariance against finite differences, observations
// at pose i - 1, the header's noise and limits, errors naming the file and line, and the
// public sim_535 run when present.
#include "datasets/islsjf_simulation.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "tests/support/public_data.hpp"
#include "tests/support/slambox_cli.hpp"

namespace slambox {
namespace {

namespace fs = std::filesystem;

TEST(IslsjfSimulation, StepCovarianceIsTheJacobianOfTheMotionModel) {
  const double v = 0.2, w = 0.3, dt = 0.3, sv = 0.02, sw = 4 * M_PI / 180;
  const UnicycleStep step = IslsjfStep(v, w, dt, sv, sw);
  EXPECT_NEAR(step.increment.x, v * dt * std::cos(w * dt), 1e-15);
  EXPECT_NEAR(step.increment.y, v * dt * std::sin(w * dt), 1e-15);
  EXPECT_NEAR(step.increment.theta, w * dt, 1e-15);
  // J by central differences of the step over (v, w), then J diag(sv^2, sw^2) J^T.
  const auto vec = [](const SE2& T) { return Eigen::Vector3d(T.x, T.y, T.theta); };
  const double h = 1e-6;
  Eigen::Matrix<double, 3, 2> J;
  J.col(0) = (vec(IslsjfStep(v + h, w, dt, 0, 0).increment) - vec(IslsjfStep(v - h, w, dt, 0, 0).increment)) / (2 * h);
  J.col(1) = (vec(IslsjfStep(v, w + h, dt, 0, 0).increment) - vec(IslsjfStep(v, w - h, dt, 0, 0).increment)) / (2 * h);
  const Eigen::Matrix3d expected = J * Eigen::Vector2d(sv * sv, sw * sw).asDiagonal() * J.transpose();
  EXPECT_LT((step.covariance - expected).cwiseAbs().maxCoeff(), 1e-12) << step.covariance << "\n" << expected;
  EXPECT_NEAR(step.covariance(2, 2), std::pow(sw * dt, 2), 1e-18);  // heading: sigma_w dt per step
}

void Write(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

// Two steps of 1 m/s for 0.5 s, turning 0 then pi rad/s; beacon 4 seen ahead from pose 0 and
// beacon 9 to the left from pose 2. Parameters in the file's own style, CRLF line ends.
fs::path TinyRun(const std::string& tag) {
  const fs::path dir = testing::FreshTempDir("islsjf_" + tag);
  Write(dir / "parameters.txt",
        "x(k+1) = x(k) + speed(k)*TimeInterval*cos(...);\r\nTimeInterval = 0.5 (s) -- between steps\r\n"
        "sigv = 0.02;   --- variance on speed noise\r\nsigomega = (4*pi/180); --- turn rate\r\n"
        "sigr = 0.1; unit: m\r\nsigtheta = (2*pi/180); unit: rad\r\n");
  Write(dir / "store_speed.txt", "1\n1\n");
  Write(dir / "store_turnrate.txt", "0\n3.141592653589793\n");
  Write(dir / "sensor_data.txt", "1 4 2.5 0 0 0 0\n3 9 1.5 1.5707963267948966 0 0 0\n");
  Write(dir / "store_robotTrue.txt", "0 0 0\n0.5 0 0\n0.8 0.3 1.57\n");
  Write(dir / "store_beaconsTrue.txt", "4 2.5 0\n9 -0.7 0.3\n");
  return dir;
}

TEST(IslsjfSimulation, FolderBecomesAStreamWithGroundTruth) {
  IslsjfSimulationReport report;
  const fs::path dir = TinyRun("ok");
  const Stream s = ReadIslsjfSimulation(dir.string(), {}, &report);
  EXPECT_EQ(report.steps, 2);
  EXPECT_EQ(report.observations, 2);
  EXPECT_EQ(report.beacons_seen, 2);
  EXPECT_TRUE(report.ground_truth);
  // Events: landmarks at 0, odometry at 0.5, odometry at 1.0, landmarks at 1.0.
  ASSERT_EQ(s.events.size(), 4u);
  const auto& first = std::get<LandmarkEvent>(s.events[0]);
  EXPECT_EQ(first.t_s, 0.0);
  EXPECT_NEAR(first.observations[0].range_m, 2.5, 1e-12);
  EXPECT_EQ(first.observations[0].id, 4);
  const auto& turn = std::get<OdometryEvent>(s.events[2]);
  EXPECT_EQ(turn.t_s, 1.0);
  EXPECT_NEAR(turn.delta.theta, M_PI / 2, 1e-12);
  EXPECT_NEAR(turn.delta.x, 0.5 * std::cos(M_PI / 2), 1e-12);
  const auto& last = std::get<LandmarkEvent>(s.events[3]);
  EXPECT_EQ(last.t_s, 1.0);  // step 3 = pose 2
  EXPECT_NEAR(last.observations[0].bearing_rad, M_PI / 2, 1e-12);
  const LandmarkSensorConfig& lm = *s.header.sensors.landmarks;
  EXPECT_NEAR(lm.sigma_range_m, 0.1, 1e-12);
  EXPECT_NEAR(lm.sigma_bearing_deg, 2.0, 1e-9);
  EXPECT_DOUBLE_EQ(lm.range_max_m, 2.5);  // the farthest observation
  EXPECT_NEAR(lm.fov_deg, 180.0, 1e-9);   // twice the widest bearing
  EXPECT_TRUE(lm.known_ids);
  EXPECT_DOUBLE_EQ(s.header.dt_s, 0.5);
  ASSERT_EQ(s.groundtruth.size(), 3u);
  EXPECT_DOUBLE_EQ(s.groundtruth[2].pose.theta, 1.57);
  EXPECT_EQ(s.header.world.landmarks.size(), 2u);
  EXPECT_EQ(s.header.scenario_name, dir.filename().string());
  EXPECT_EQ(ReadIslsjfSimulation(dir.string() + "/").header.scenario_name, dir.filename().string());
}

TEST(IslsjfSimulation, OptionsOverrideTheFile) {
  const fs::path dir = TinyRun("options");
  Write(dir / "parameters.txt", "nothing here\n");
  IslsjfSimulationOptions o;
  o.time_interval_s = 0.25, o.sigma_speed_mps = 0.01, o.sigma_turnrate_deg_s = 1, o.sigma_range_m = 0.2;
  o.sigma_bearing_deg = 3, o.range_max_m = 3.0, o.fov_deg = 200;
  const Stream s = ReadIslsjfSimulation(dir.string(), o);
  const LandmarkSensorConfig& lm = *s.header.sensors.landmarks;
  EXPECT_DOUBLE_EQ(s.header.dt_s, 0.25);
  EXPECT_NEAR(lm.sigma_range_m, 0.2, 1e-12);
  EXPECT_NEAR(lm.sigma_bearing_deg, 3.0, 1e-9);
  EXPECT_DOUBLE_EQ(lm.range_max_m, 3.0);
  EXPECT_DOUBLE_EQ(lm.fov_deg, 200.0);
}

void ExpectError(const fs::path& dir, const std::string& file, int line, const std::string& words) {
  try {
    ReadIslsjfSimulation(dir.string());
    FAIL() << "no error; expected: " << words;
  } catch (const InputError& e) {
    EXPECT_NE(e.file().find(file), std::string::npos) << e.what();
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(IslsjfSimulation, BadInputNamesTheFileAndLine) {
  fs::path dir = TinyRun("bad1");
  Write(dir / "sensor_data.txt", "1 4 2.5 0 0 0 0\n2 4 nan 0 0 0 0\n");
  ExpectError(dir, "sensor_data.txt", 2, "'nan'");
  Write(dir / "sensor_data.txt", "1 4 2.5 0\n9 4 1 0\n");
  ExpectError(dir, "sensor_data.txt", 2, "not a whole number in 1 .. 3");
  Write(dir / "sensor_data.txt", "1 4 -1 0\n");
  ExpectError(dir, "sensor_data.txt", 1, "is not in (0, ");
  Write(dir / "sensor_data.txt", "1 4 1e300 0\n");
  ExpectError(dir, "sensor_data.txt", 1, "is not in (0, ");
  Write(dir / "sensor_data.txt", "1 4 2\n");
  ExpectError(dir, "sensor_data.txt", 1, "expected `step id range bearing");
  dir = TinyRun("bad2");
  Write(dir / "store_turnrate.txt", "0\n");
  ExpectError(dir, "store_turnrate.txt", 0, "1 turn rates for 2 speeds");
  Write(dir / "store_turnrate.txt", "0\n1e300\n");
  ExpectError(dir, "store_speed.txt", 0, "step 2 moves farther");
  dir = TinyRun("bad3");
  Write(dir / "parameters.txt", "TimeInterval = 0.5\nsigv = 0.02;\n");
  ExpectError(dir, "parameters.txt", 0, "no 'sigomega = ...' line");
  dir = TinyRun("bad4");
  Write(dir / "store_robotTrue.txt", "0 0 0\n0.5 0 0\n");
  ExpectError(dir, "", 0, "ground truth for 2 poses, the chain has 3");
  dir = TinyRun("bad5");
  fs::remove(dir / "store_speed.txt");
  ExpectError(dir, "store_speed.txt", 0, "");
  ExpectError(dir / "missing", "missing", 0, "not a directory");
}

TEST(IslsjfSimulation, PublicSim535WhenPresent) {
  const std::string dir = testing::PublicDataFile(SLAMBOX_SOURCE_DIR, "landmark/sim_535");
  if (dir.empty()) GTEST_SKIP() << "landmark/sim_535 not found; set SLAMBOX_DATA";
  IslsjfSimulationReport report;
  const Stream s = ReadIslsjfSimulation(dir, {}, &report);
  EXPECT_EQ(report.steps, 535);
  EXPECT_EQ(report.observations, 850);
  EXPECT_EQ(report.beacons_seen, 28);
  EXPECT_DOUBLE_EQ(report.time_interval_s, 0.3);
  EXPECT_NEAR(report.range_max_m, 3.1689425, 1e-9);
  EXPECT_EQ(s.groundtruth.size(), 536u);
  EXPECT_EQ(s.header.world.landmarks.size(), 196u);
  EXPECT_NEAR(s.groundtruth.back().pose.x, 25.52808229, 1e-8);  // store_robotTrue.txt's last row
  // The measured speeds and turn rates integrated step by step reach the file's own
  // dead-reckoning end (store_robotOdo.txt's last row).
  SE2 pose = s.header.start_pose;
  for (const SensorEvent& e : s.events)
    if (const auto* odo = std::get_if<OdometryEvent>(&e)) pose = pose * odo->delta;
  EXPECT_NEAR(pose.x, 25.02053303, 1e-6);
  EXPECT_NEAR(pose.y, 23.54028156, 1e-6);
  EXPECT_NEAR(pose.theta, -0.36633296, 1e-6);
}

}  // namespace
}  // namespace slambox
