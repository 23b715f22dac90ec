// Victoria Park conversion: odometry chain and observations into a stream (range,
// bearing, known ids, times k * period), the header's noise from the file's covariances
// (closed form), errors naming the line, and the public file when present.
#include "datasets/victoria_park.hpp"

#include <gtest/gtest.h>

#include <set>

#include "core/error.hpp"
#include "tests/support/public_data.hpp"

namespace slambox {
namespace {

// Pose 0 sees tree 7 straight ahead at 10 m; pose 1 (1 m ahead, turned 0.1 rad) sees
// tree 7 and tree 3 at (0, 5): covariances diag(0.04, 0.01) give sigma_range 0.2 and
// sigma_bearing 0.01 rad (= 0.1 m / 10 m) for the first, and for (0, 5) range variance
// P_yy = 0.01 -> 0.1 and bearing sqrt(0.04) / 5 = 0.04 rad.
const char* kData =
    "0 0 7 10 0 0.04 0 0.01 0 0 0 0\n"
    "1 0 1 1 0 0.1 0 0 0 0 0 0\n"
    "0 1 7 9 0.9 0.04 0 0.01 0 0 0 0\n"
    "0 1 3 0 5 0.04 0 0.01 0 0 0 0\n";

TEST(VictoriaPark, ChainAndObservationsBecomeAStream) {
  const Stream s = ParseVictoriaPark(kData, "vp.txt", {.pose_period_s = 0.5});
  ASSERT_EQ(s.events.size(), 3u);  // landmarks at 0, odometry at 0.5, landmarks at 0.5
  const auto& first = std::get<LandmarkEvent>(s.events[0]);
  EXPECT_EQ(first.t_s, 0.0);
  ASSERT_EQ(first.observations.size(), 1u);
  EXPECT_DOUBLE_EQ(first.observations[0].range_m, 10.0);
  EXPECT_DOUBLE_EQ(first.observations[0].bearing_rad, 0.0);
  EXPECT_EQ(first.observations[0].id, 7);
  const auto& odo = std::get<OdometryEvent>(s.events[1]);
  EXPECT_EQ(odo.t_s, 0.5);
  EXPECT_DOUBLE_EQ(odo.delta.theta, 0.1);
  const auto& second = std::get<LandmarkEvent>(s.events[2]);
  EXPECT_DOUBLE_EQ(second.observations[1].bearing_rad, M_PI / 2);
  const LandmarkSensorConfig& lm = *s.header.sensors.landmarks;
  EXPECT_TRUE(lm.known_ids);
  EXPECT_EQ(lm.range_max_m, 10.0);
  // Medians over the three observations: ranges {0.2, ~0.199, 0.1} m, bearings {0.01, ~0.011, 0.04} rad;
  // the middle ones are J P J^T at (9, 0.9): J = [[x, y] / r; [-y, x] / r^2].
  const double r = std::hypot(9.0, 0.9);
  EXPECT_NEAR(lm.sigma_range_m, std::sqrt(0.04 * std::pow(9 / r, 2) + 0.01 * std::pow(0.9 / r, 2)), 1e-12);
  const double b2 = std::sqrt(0.04 * std::pow(0.9 / 81.81, 2) + 0.01 * std::pow(9 / 81.81, 2));  // J P J^T at (9, 0.9)
  EXPECT_NEAR(lm.sigma_bearing_deg, b2 * 180 / M_PI, 1e-9);
  EXPECT_TRUE(s.groundtruth.empty());
  EXPECT_DOUBLE_EQ(s.header.duration_s, 0.5);
}

void ExpectErrorAtLine(const std::string& text, int line, const std::string& words) {
  try {
    ParseVictoriaPark(text, "bad.txt");
    FAIL() << "no error for: " << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

TEST(VictoriaPark, BadRowsNameTheLine) {
  const std::string ok = "1 0 1 1 0 0 0 0 0 0 0 0\n";
  ExpectErrorAtLine(ok + "1 1 3 1 0 0 0 0 0 0 0 0\n", 2, "consecutive poses");
  ExpectErrorAtLine(ok + "0 1 2 1 0 0 0 0\n", 2, "expected 12 fields");
  ExpectErrorAtLine(ok + "0 1 x 1 0 0 0 0 0 0 0 0\n", 2, "'x'");
  ExpectErrorAtLine(ok + "2 1 2 1 0 0 0 0 0 0 0 0\n", 2, "1 (odometry) or 0");
  ExpectErrorAtLine(ok + "0 1 -2 1 0 0 0 0 0 0 0 0\n", 2, "non-negative whole");
  ExpectErrorAtLine(ok + "0 5 2 1 0 0 0 0 0 0 0 0\n", 0, "beyond the last");
  ExpectErrorAtLine("0 0 2 1 0 0 0 0 0 0 0 0\n", 0, "no odometry row");
}

TEST(VictoriaPark, PublicFileWhenPresent) {
  const std::string path =
      testing::PublicDataFile(SLAMBOX_SOURCE_DIR, "landmark/victoria_park/islsjf/VicPark_clean_data.txt");
  if (path.empty()) GTEST_SKIP() << "public data absent (../shared/data or $SLAMBOX_DATA)";
  const Stream s = ReadVictoriaPark(path);
  size_t steps = 0, observations = 0;
  std::set<int> trees;
  for (const SensorEvent& e : s.events) {
    steps += std::holds_alternative<OdometryEvent>(e);
    if (const auto* l = std::get_if<LandmarkEvent>(&e))
      for (const auto& o : l->observations) ++observations, trees.insert(o.id);
  }
  EXPECT_EQ(steps, 6898u);         // rows starting with 1
  EXPECT_EQ(observations, 45390u);  // rows starting with 0
  EXPECT_GT(trees.size(), 100u);
}

}  // namespace
}  // namespace slambox
