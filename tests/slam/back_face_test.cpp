// Back faces (slam/back_face.hpp): normals turned towards the sensor that saw them, and a
// match one corridor width over (the new scan's walls on the target's, its sensor beyond the
// target's wall) seen as back faces, while the true match sees none.
#include <gtest/gtest.h>

#include <random>

#include "slam/back_face.hpp"
#include "slam/icp_target.hpp"
#include "slam/scan_points.hpp"
#include "tests/support/synthetic_scan.hpp"

namespace slambox {
namespace {

TEST(BackFace, NormalsTurnTowardsTheirSensor) {
  // A wall along x at y = 1 seen from below (sensor at the origin) and one at y = 3 seen
  // from above (sensor at y = 5): PCA's normals have either sign until oriented.
  std::vector<Eigen::Vector2d> points, viewpoints;
  for (int i = 0; i < 20; ++i) {
    points.emplace_back(0.05 * i, 1.0), viewpoints.emplace_back(0.0, 0.0);
    points.emplace_back(0.05 * i, 3.0), viewpoints.emplace_back(0.3, 5.0);
  }
  points.emplace_back(10.0, 10.0), viewpoints.emplace_back(0.0, 0.0);  // alone: no normal
  IcpTarget t = MakeCloudTarget(points);
  OrientNormalsTowards(&t, viewpoints);
  ASSERT_EQ(t.normals.size(), points.size());
  for (size_t i = 0; i + 1 < points.size(); ++i) {
    const double expected_y = points[i].y() == 1.0 ? -1.0 : 1.0;
    EXPECT_NEAR(t.normals[i].y(), expected_y, 1e-9) << i;
  }
  EXPECT_TRUE(t.normals.back().isZero());
}

TEST(BackFace, OneCorridorWidthOverSeesTheWallsFromBehind) {
  // A 1.4 m corridor along x; both scans (full circle) taken on its centre line.
  const std::vector<Segment> walls = {{{-30, -0.7}, {30, -0.7}}, {{-30, 0.7}, {30, 0.7}}};
  std::mt19937_64 rng(7);
  const LaserScanEvent target_scan = testing::RayCastScan(walls, SE2(0, 0, 0), 360, 0.01, rng, 10.0);
  const LaserScanEvent source_scan = testing::RayCastScan(walls, SE2(0.3, 0, 0), 360, 0.01, rng, 10.0);
  const ScanPoints tp = ScanToPoints(target_scan), sp = ScanToPoints(source_scan);
  IcpTarget target = MakeCloudTarget(tp.points);
  OrientNormalsTowards(&target, std::vector<Eigen::Vector2d>(tp.points.size(), Eigen::Vector2d::Zero()));

  const BackFaceResult truth = BackFaces(sp.points, target, SE2(0.3, 0, 0));
  EXPECT_GT(truth.matched, 100);
  EXPECT_EQ(truth.back_faces, 0);
  EXPECT_EQ(truth.fraction, 0.0);
  // One width over: the source's lower wall lies on the target's upper wall, its upper wall
  // on nothing, its sensor 0.7 m beyond the target's upper wall.
  const BackFaceResult over = BackFaces(sp.points, target, SE2(0.3, 1.4, 0));
  EXPECT_GT(over.matched, 50);
  EXPECT_EQ(over.back_faces, over.matched);
  EXPECT_EQ(over.fraction, 1.0);
  // Points beyond max_distance_m are no evidence either way.
  const BackFaceResult apart = BackFaces(sp.points, target, SE2(0.3, 5.0, 0));
  EXPECT_EQ(apart.matched, 0);
  EXPECT_EQ(apart.fraction, 0.0);
}

}  // namespace
}  // namespace slambox
