// Landmark detector: line of sight, field of view, detection probability and clutter.
#include "sim/landmark_sensor.hpp"

#include <gtest/gtest.h>

#include <set>

#include "noise_statistics.hpp"

namespace slambox {
namespace {

std::set<int> SeenIds(const LandmarkEvent& e) {
  std::set<int> ids;
  for (const auto& o : e.observations) ids.insert(o.id);
  return ids;
}

TEST(LandmarkSensor, WallsMoversAndPostsOcclude) {
  // Robot at the origin facing +x. Post 0 behind a wall, post 1 beside the wall's end,
  // post 2 behind post 3, post 4 behind a mover, post 5 in front of the wall.
  std::vector<TrueLandmark> posts = {{0, {6, 0}, 0.1}, {1, {6, 3}, 0.1}, {2, {0, 8}, 0.1},
                                     {3, {0, 4}, 0.2}, {4, {-6, 0}, 0.1}, {5, {4, -0.5}, 0.1}};
  StaticGeometry g;
  g.segments.push_back({{5, -1}, {5, 1}});
  for (const auto& p : posts) g.circles.push_back({p.position, p.radius_m});
  const StaticGeometryIndex index(g);
  MoverShape person;
  person.T_world_mover = SE2(-3, 0, 0);
  person.radius_m = 0.3;
  LandmarkSensor sensor(LandmarkSensorConfig{.sigma_range_m = 0, .sigma_bearing_deg = 0}, 1);
  const LandmarkEvent e = sensor.Detect(0.0, SE2(), posts, RayScene{&index, {person}});
  EXPECT_EQ(SeenIds(e), (std::set<int>{1, 3, 5}));
  // Without the mover, post 4 is seen; exact range and bearing with noise off.
  const LandmarkEvent e2 = sensor.Detect(0.0, SE2(), posts, RayScene{&index, {}});
  EXPECT_EQ(SeenIds(e2), (std::set<int>{1, 3, 4, 5}));
  for (const auto& o : e2.observations)
    if (o.id == 4) {
      EXPECT_NEAR(o.range_m, 6.0, 1e-12);
      EXPECT_NEAR(std::abs(o.bearing_rad), M_PI, 1e-12);
    }
}

TEST(LandmarkSensor, RangeAndFieldOfView) {
  std::vector<TrueLandmark> posts = {{0, {3, 0}, 0.1}, {1, {0, 3}, 0.1}, {2, {20, 0}, 0.1}, {3, {2, 1.5}, 0.1}};
  StaticGeometry g;
  for (const auto& p : posts) g.circles.push_back({p.position, p.radius_m});
  const StaticGeometryIndex index(g);
  LandmarkSensor sensor(LandmarkSensorConfig{.range_max_m = 15, .fov_deg = 90, .known_ids = false}, 1);
  const LandmarkEvent e = sensor.Detect(0.0, SE2(), posts, RayScene{&index, {}});
  ASSERT_EQ(e.observations.size(), 2u);  // posts 0 and 3 (bearing 36.9 deg); 1 is at 90 deg, 2 too far
  for (const auto& o : e.observations) EXPECT_EQ(o.id, -1);  // ids unknown
}

TEST(LandmarkSensor, DetectionProbabilityAndPoissonClutter) {
  std::vector<TrueLandmark> posts = {{0, {3, 0}, 0.1}, {1, {0, 3}, 0.1}, {2, {-3, 0}, 0.1}};
  StaticGeometry g;
  for (const auto& p : posts) g.circles.push_back({p.position, p.radius_m});
  const StaticGeometryIndex index(g);
  LandmarkSensorConfig cfg{.range_max_m = 10, .fov_deg = 360, .detection_prob = 0.7, .clutter_per_scan = 2.5};
  LandmarkSensor sensor(cfg, 9);
  const int scans = 4000;
  double detected = 0, clutter = 0;
  for (int k = 0; k < scans; ++k) {
    for (const auto& o : sensor.Detect(0.0, SE2(), posts, RayScene{&index, {}}).observations) {
      if (o.id >= 0) {
        ++detected;
      } else {
        ++clutter;
        EXPECT_GE(o.range_m, 0.0);
        EXPECT_LE(o.range_m, 10.0);
      }
    }
  }
  testing::ExpectBinomial(detected, 3.0 * scans, 0.7, "detections");
  // Sum of Poisson(2.5) over the scans is Poisson(2.5 scans): 4 sigma = 4 sqrt(mean).
  EXPECT_NEAR(clutter, 2.5 * scans, 4.0 * std::sqrt(2.5 * scans));
}

}  // namespace
}  // namespace slambox
