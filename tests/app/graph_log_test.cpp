// `convert graph`'s conversion (app/graph_log.hpp + datasets/landmark_log.hpp): a tiny iSAM
// graph -> exact stream events and noise, a step stated backwards -> the inverse with its
// covariance J C J^T (J against finite differences, many random states), the g2o variant,
// off-chain edges counted, and the errors a user sees for graphs that are not one chain.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <variant>

#include "app/graph_log.hpp"
#include "core/error.hpp"
#include "tests/support/slambox_cli.hpp"

namespace slambox {
namespace {

namespace fs = std::filesystem;

// Pose 0 at the origin, 1 m ahead twice, turning left at pose 2; tree 7 at (3, 4) and tree
// 8 at (1, 2) in the world. iSAM's square-root information: sigma 0.1 m, 0.05 rad; 0.1 m.
const char* kTinyIsam =
    "# a chain of three poses\n"
    "ODOMETRY 0 1 1 0 0 10 0 0 10 0 20\n"
    "ODOMETRY 1 2 1 0 1.5707963267948966 10 0 0 10 0 20\n"
    "LANDMARK 0 7 3 4 10 0 10\n"
    "LANDMARK 1 8 0 2 10 0 10\n"
    "LANDMARK 2 7 4 -1 10 0 10\n";

GraphLog Convert(const std::string& text, const std::string& name, IsamNoise noise = IsamNoise::kAuto) {
  return ChainLandmarkLog(ParsePoseGraph(text, name, {.isam_noise = noise}), name);
}

/// The InputError that `f` throws (fails the test when it throws none).
template <class F>
InputError ErrorOf(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError";
  return InputError("", 0, "", "");
}

std::string Contents(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return path.string();
}

TEST(GraphLog, TinyIsamGraphGivesExactEvents) {
  const GraphLog g = Convert(kTinyIsam, "tiny.txt");
  EXPECT_EQ(g.report.odometry_steps, 2);
  EXPECT_EQ(g.report.reversed_steps, 0);
  EXPECT_EQ(g.report.off_chain_edges, 0);
  EXPECT_EQ(g.report.sightings, 3);
  EXPECT_EQ(g.report.landmarks, 2);
  ASSERT_EQ(g.report.isam_noise, IsamNoise::kSqrtInformation);
  const Eigen::Matrix3d step_covariance = Eigen::Vector3d(0.01, 0.01, 0.0025).asDiagonal();
  for (const Eigen::Matrix3d& c : g.log.increment_covariances) EXPECT_TRUE(c.isApprox(step_covariance, 1e-12)) << c;

  const Stream s = AssembleLandmarkLog(g.log, "tiny.txt", {.pose_period_s = 1.0, .fov_deg = 360.0});
  ASSERT_TRUE(s.header.sensors.landmarks);
  EXPECT_FALSE(s.header.sensors.landmarks->detection_prob_known);  // a graph lists sightings, not misses
  struct Expected {
    double t_s;
    std::optional<SE2> delta;  ///< an odometry event, else a landmark event with `seen`
    LandmarkObservation seen;
  };
  const std::vector<Expected> expected = {
      {0.0, std::nullopt, {5.0, std::atan2(4.0, 3.0), 7}},
      {1.0, SE2(1, 0, 0), {}},
      {1.0, std::nullopt, {2.0, M_PI / 2, 8}},
      {2.0, SE2(1, 0, M_PI / 2), {}},
      {2.0, std::nullopt, {std::sqrt(17.0), std::atan2(-1.0, 4.0), 7}},
  };
  ASSERT_EQ(s.events.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) {
    const Expected& x = expected[i];
    EXPECT_EQ(EventTime(s.events[i]), x.t_s) << i;
    if (x.delta) {
      const auto* odo = std::get_if<OdometryEvent>(&s.events[i]);
      ASSERT_NE(odo, nullptr) << i;
      EXPECT_EQ(odo->delta.vector(), x.delta->vector()) << i;
      continue;
    }
    const auto* lm = std::get_if<LandmarkEvent>(&s.events[i]);
    ASSERT_NE(lm, nullptr) << i;
    ASSERT_EQ(lm->observations.size(), 1u) << i;
    EXPECT_DOUBLE_EQ(lm->observations[0].range_m, x.seen.range_m) << i;
    EXPECT_DOUBLE_EQ(lm->observations[0].bearing_rad, x.seen.bearing_rad) << i;
    EXPECT_EQ(lm->observations[0].id, x.seen.id) << i;
  }
  // sigma_bearing = 0.1 m / range: 0.02, 0.05, 0.1 / sqrt(17) rad; the median is the last.
  const LandmarkSensorConfig& sensor = *s.header.sensors.landmarks;
  EXPECT_NEAR(sensor.sigma_range_m, 0.1, 1e-12);
  EXPECT_NEAR(sensor.sigma_bearing_deg, 0.1 / std::sqrt(17.0) * 180.0 / M_PI, 1e-9);
  EXPECT_EQ(sensor.range_max_m, 5.0);
  EXPECT_TRUE(sensor.known_ids);
  EXPECT_EQ(s.header.duration_s, 2.0);
  EXPECT_TRUE(s.groundtruth.empty());
}

// f(x, y, theta) = (x, y, theta)^-1 differentiated numerically (central differences).
Eigen::Matrix3d NumericJacobianOfInverse(const SE2& T) {
  Eigen::Matrix3d J;
  const double h = 1e-6;
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d plus = T.vector(), minus = T.vector();
    plus(k) += h, minus(k) -= h;
    J.col(k) = (SE2::FromVector(plus).inverse().vector() - SE2::FromVector(minus).inverse().vector()) / (2 * h);
  }
  return J;
}

TEST(GraphLog, BackwardStepIsInvertedWithItsCovarianceMapped) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> position(-5.0, 5.0), angle(-3.0, 3.0), entry(-0.1, 0.1);
  for (int trial = 0; trial < 100; ++trial) {
    const SE2 T(position(rng), position(rng), angle(rng));  // pose 0 in pose 1's frame
    Eigen::Matrix3d A;
    for (int i = 0; i < 9; ++i) A(i) = entry(rng);
    const Eigen::Matrix3d C = A * A.transpose() + 1e-3 * Eigen::Matrix3d::Identity();
    char text[512];
    std::snprintf(text, sizeof text,
                  "ODOMETRY 1 0 %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\nLANDMARK 0 0 1 0 0.01 0 0.01\n", T.x,
                  T.y, T.theta, C(0, 0), C(0, 1), C(0, 2), C(1, 1), C(1, 2), C(2, 2));
    const GraphLog g = Convert(text, "backward.txt", IsamNoise::kCovariance);
    ASSERT_EQ(g.report.reversed_steps, 1);
    ASSERT_EQ(g.log.increments.size(), 1u);
    const SE2 inverse = T.inverse();
    EXPECT_LT((g.log.increments[0].vector() - inverse.vector()).norm(), 1e-12) << trial;
    const Eigen::Matrix3d J = NumericJacobianOfInverse(T);
    const Eigen::Matrix3d want = J * C * J.transpose();
    EXPECT_LT((g.log.increment_covariances[0] - want).norm(), 1e-7 * want.norm()) << trial << "\n"
                                                                                  << g.log.increment_covariances[0];
    // The same step stated forwards is taken as it is.
    std::snprintf(text, sizeof text,
                  "ODOMETRY 0 1 %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\nLANDMARK 0 0 1 0 0.01 0 0.01\n",
                  inverse.x, inverse.y, inverse.theta, want(0, 0), want(0, 1), want(0, 2), want(1, 1), want(1, 2),
                  want(2, 2));
    const GraphLog forward = Convert(text, "forward.txt", IsamNoise::kCovariance);
    EXPECT_EQ(forward.report.reversed_steps, 0);
    EXPECT_LT((forward.log.increment_covariances[0] - g.log.increment_covariances[0]).norm(), 1e-7 * want.norm());
  }
}

TEST(GraphLog, G2oPointsAndOffChainEdges) {
  const char* text =
      "VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 1 0 0\nVERTEX_SE2 2 2 0 0\nVERTEX_XY 10 3 4\n"
      "EDGE_SE2 0 1 1 0 0 100 0 0 100 0 400\n"
      "EDGE_SE2 1 2 1 0 0 100 0 0 100 0 400\n"
      "EDGE_SE2 0 2 2 0 0 100 0 0 100 0 400\n"  // a loop closure
      "EDGE_SE2 2 1 -1 0 0 100 0 0 100 0 400\n"  // the step 1 -> 2 again, backwards
      "EDGE_SE2_XY 1 10 2 4 25 0 100\n";
  const GraphLog g = Convert(text, "points.g2o");
  EXPECT_FALSE(g.report.isam_noise.has_value());
  EXPECT_EQ(g.report.odometry_steps, 2);
  EXPECT_EQ(g.report.reversed_steps, 0);
  EXPECT_EQ(g.report.off_chain_edges, 2);
  ASSERT_EQ(g.log.sightings.size(), 1u);
  const LandmarkLog::Sighting& s = g.log.sightings[0];
  EXPECT_EQ(s.pose, 1);
  EXPECT_EQ(s.landmark, 10);  // the file's id, shared with the poses in g2o
  EXPECT_EQ(s.point, Eigen::Vector2d(2, 4));
  EXPECT_TRUE(s.covariance.isApprox(Eigen::Vector2d(0.04, 0.01).asDiagonal().toDenseMatrix(), 1e-12)) << s.covariance;
}

TEST(GraphLog, GraphsThatAreNotOneChainAreRefused) {
  const std::string step = " 1 0 0 10 0 0 10 0 10\n";
  // Ids 0, 1, 5, 6: nothing joins 1 and 5.
  InputError gap = ErrorOf([&] { Convert("ODOMETRY 0 1" + step + "ODOMETRY 5 6" + step + "LANDMARK 0 0 1 0 10 0 10\n", "gap.txt"); });
  EXPECT_EQ(gap.file(), "gap.txt");
  EXPECT_NE(std::string(gap.what()).find("no pose edge joins poses 1 and 5"), std::string::npos) << gap.what();
  // A loop closure does not fill a gap.
  gap = ErrorOf([&] { Convert("ODOMETRY 0 1" + step + "ODOMETRY 0 2" + step + "LANDMARK 0 0 1 0 10 0 10\n", "gap.txt"); });
  EXPECT_NE(std::string(gap.what()).find("poses 1 and 2"), std::string::npos) << gap.what();
  const InputError pose_only = ErrorOf([&] { Convert("ODOMETRY 0 1" + step, "pose_only.txt"); });
  EXPECT_EQ(pose_only.file(), "pose_only.txt");
  EXPECT_NE(std::string(pose_only.what()).find("no landmark edge"), std::string::npos) << pose_only.what();
  EXPECT_NE(std::string(pose_only.what()).find("slambox optimize"), std::string::npos) << pose_only.what();
  const InputError single = ErrorOf([&] {
    const GraphLog g = Convert("VERTEX_SE2 0 0 0 0\nVERTEX_XY 1 1 0\nEDGE_SE2_XY 0 1 1 0 1 0 1\n", "single.g2o");
    AssembleLandmarkLog(g.log, "single.g2o", {.pose_period_s = 1.0, .fov_deg = 360.0});
  });
  EXPECT_NE(std::string(single.what()).find("no odometry step"), std::string::npos) << single.what();
}

TEST(GraphLog, GroundTruthMatchedByIdFromEitherFile) {
  const fs::path dir = testing::FreshTempDir("graph_log_truth");
  const std::string graph = Contents(dir / "tiny.txt", kTinyIsam);
  const std::string poses = Contents(dir / "poses.txt", "0 0 0 0\n1 1 0 0\n2 2 0 1.5707963267948966\n3 9 9 0\n");
  const std::string trees = Contents(dir / "trees.txt", "# id x y\n7 3 4\n8 1 2\n9 5 5\n");
  const GraphLog g = ReadGraphLog(graph, {.groundtruth = {trees, poses}});
  ASSERT_EQ(g.log.true_poses.size(), 3u);  // pose 3 is not in the graph
  EXPECT_EQ(g.log.true_poses[2].vector(), SE2(2, 0, M_PI / 2).vector());
  ASSERT_EQ(g.log.true_landmarks.size(), 2u);
  EXPECT_EQ(g.log.true_landmarks.at(8), Eigen::Vector2d(1, 2));
  const Stream s = AssembleLandmarkLog(g.log, graph, {.pose_period_s = 0.5, .fov_deg = 360.0});
  ASSERT_EQ(s.groundtruth.size(), 3u);
  EXPECT_EQ(s.groundtruth[2].t_s, 1.0);
  EXPECT_EQ(s.header.world.landmarks.size(), 2u);

  const std::string no_pose_2 = Contents(dir / "no_pose_2.txt", "0 0 0 0\n1 1 0 0\n");
  InputError e = ErrorOf([&] { ReadGraphLog(graph, {.groundtruth = {trees, no_pose_2}}); });
  EXPECT_EQ(e.file(), no_pose_2);
  EXPECT_NE(std::string(e.what()).find("no true pose for pose id 2"), std::string::npos) << e.what();
  const std::string no_tree_8 = Contents(dir / "no_tree_8.txt", "7 3 4\n");
  e = ErrorOf([&] { ReadGraphLog(graph, {.groundtruth = {poses, no_tree_8}}); });
  EXPECT_EQ(e.file(), no_tree_8);
  EXPECT_NE(std::string(e.what()).find("landmark id 8"), std::string::npos) << e.what();
  fs::remove_all(dir);
}

TEST(GraphLog, BadFilesNameTheirLine) {
  const fs::path dir = testing::FreshTempDir("graph_log_bad");
  const std::string nan = Contents(dir / "nan.txt", "ODOMETRY 0 1 1 0 0 10 0 0 10 0 10\nLANDMARK 1 0 nan 0 10 0 10\n");
  InputError e = ErrorOf([&] { ReadGraphLog(nan); });
  EXPECT_EQ(e.file(), nan);
  EXPECT_EQ(e.line(), 2);
  const std::string unknown = Contents(dir / "unknown.g2o",
                                       "VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 1 0 0\nVERTEX_XY 5 1 1\n"
                                       "EDGE_SE2 0 1 1 0 0 1 0 0 1 0 1\nEDGE_SE2_XY 1 6 0 1 1 0 1\n");
  e = ErrorOf([&] { ReadGraphLog(unknown); });
  EXPECT_EQ(e.line(), 5);
  EXPECT_NE(std::string(e.what()).find("point 6"), std::string::npos) << e.what();
  const std::string huge = Contents(dir / "huge.txt", "ODOMETRY 0 1 1e300 0 0 10 0 0 10 0 10\nLANDMARK 1 0 1 0 10 0 10\n");
  e = ErrorOf([&] { ReadGraphLog(huge); });
  EXPECT_EQ(e.line(), 1);
  const std::string absent = (dir / "absent.txt").string();
  e = ErrorOf([&] { ReadGraphLog(absent); });
  EXPECT_EQ(e.file(), absent);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace slambox
