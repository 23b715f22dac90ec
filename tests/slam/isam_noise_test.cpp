// The two conventions of iSAM-family graph lines (slam/isam_noise.hpp): iSAM's square-root
// information and GTSAM's covariance, decided per file, and the reader using the decision.
#include "slam/isam_noise.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>

#include "core/error.hpp"
#include "slam/g2o_io.hpp"
#include "tests/support/public_data.hpp"

namespace slambox {
namespace {

TEST(IsamNoise, TheDiagonalDecidesTheConventionPerFile) {
  // iSAM (manhattanOlson3500, cityTrees10000): 1/sigma > 1; GTSAM (victoria_park_gtsam): sigma^2 < 1.
  const std::string isam = "ODOMETRY 0 1 1 0 0 44.7 0 0 44.7 0 44.7\nLANDMARK 1 7 2 1 10 0 10\n";
  const std::string gtsam = "ODOMETRY 0 1 1 0 0 0.0001 0 0 4e-06 0 4e-06\nLANDMARK 1 7 2 1 0.4 0 0.4\n";
  EXPECT_EQ(ResolveIsamNoise(isam, "a.txt", IsamNoise::kAuto, true), IsamNoise::kSqrtInformation);
  EXPECT_EQ(ResolveIsamNoise(gtsam, "b.txt", IsamNoise::kAuto, true), IsamNoise::kCovariance);
  EXPECT_EQ(ResolveIsamNoise("VERTEX_SE2 0 0 0 0\n", "c.g2o", IsamNoise::kAuto, false), std::nullopt);
  // EDGE2 counts only in an iSAM file; a TORO file's EDGE2 is information, not this.
  EXPECT_EQ(ResolveIsamNoise("EDGE2 0 1 1 0 0 0.5 0 0 0.5 0 0.5\n", "t.graph", IsamNoise::kAuto, false), std::nullopt);
  // Sigma = 1 everywhere reads the same either way: iSAM's.
  EXPECT_EQ(ResolveIsamNoise("ODOMETRY 0 1 1 0 0 1 0 0 1 0 1\n", "d.txt", IsamNoise::kAuto, true), IsamNoise::kSqrtInformation);
  // Given explicitly, the file's values do not matter.
  EXPECT_EQ(ResolveIsamNoise(gtsam, "b.txt", IsamNoise::kSqrtInformation, true), IsamNoise::kSqrtInformation);
  try {
    ResolveIsamNoise("ODOMETRY 0 1 1 0 0 50 0 0 50 0 100\n# c\nLANDMARK 1 7 2 1 0.4 0 0.4\n", "mixed.txt", IsamNoise::kAuto,
                     true);
    FAIL() << "a file with both kinds of values must be refused";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_NE(std::string(e.what()).find("line 1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--noise"), std::string::npos) << e.what();
  }
}

TEST(IsamNoise, CovarianceIsInvertedAndSquareRootSquared) {
  const double v[6] = {0.04, 0.01, 0.002, 0.09, 0.003, 0.0004};
  const std::optional<Eigen::Matrix3d> from_cov = IsamPoseInformation(v, IsamNoise::kCovariance);
  ASSERT_TRUE(from_cov);
  Eigen::Matrix3d C;
  C << 0.04, 0.01, 0.002, 0.01, 0.09, 0.003, 0.002, 0.003, 0.0004;
  EXPECT_LT(((*from_cov) * C - Eigen::Matrix3d::Identity()).norm(), 1e-10);
  const std::optional<Eigen::Matrix3d> from_sqrt = IsamPoseInformation(v, IsamNoise::kSqrtInformation);
  ASSERT_TRUE(from_sqrt);
  Eigen::Matrix3d R;
  R << 0.04, 0.01, 0.002, 0, 0.09, 0.003, 0, 0, 0.0004;
  EXPECT_LT((*from_sqrt - R.transpose() * R).norm(), 1e-15);
  const double point[3] = {0.4, 0.1, 0.4};
  Eigen::Matrix2d Cp;
  Cp << 0.4, 0.1, 0.1, 0.4;
  EXPECT_LT((*IsamPointInformation(point, IsamNoise::kCovariance) - Cp.inverse()).norm(), 1e-12);
  // Not positive definite: a covariance with a negative determinant, a root with a zero diagonal.
  const double indefinite[3] = {0.1, 0.5, 0.1}, singular[3] = {10, 0, 0};
  EXPECT_FALSE(IsamPointInformation(indefinite, IsamNoise::kCovariance));
  EXPECT_FALSE(IsamPointInformation(singular, IsamNoise::kSqrtInformation));
}

TEST(IsamNoise, TheReaderUsesTheFilesConvention) {
  const std::string gtsam = "ODOMETRY 0 1 1 0 0 0.0001 0 0 4e-06 0 4e-06\nLANDMARK 1 7 2 1 0.4 0 0.4\n";
  const PoseGraphFile f = ParsePoseGraph(gtsam, "vp.txt");
  ASSERT_EQ(f.isam_noise, IsamNoise::kCovariance);
  EXPECT_NEAR(f.graph.edges[0].information(0, 0), 1e4, 1e-6);
  EXPECT_NEAR(f.graph.edges[0].information(2, 2), 2.5e5, 1e-4);
  EXPECT_NEAR(f.graph.landmark_edges[0].information(0, 0), 2.5, 1e-12);
  const PoseGraphFile as_root = ParsePoseGraph(gtsam, "vp.txt", {.isam_noise = IsamNoise::kSqrtInformation});
  EXPECT_NEAR(as_root.graph.edges[0].information(0, 0), 1e-8, 1e-20);
  EXPECT_EQ(ParsePoseGraph("VERTEX_SE2 0 0 0 0\n", "p.g2o").isam_noise, std::nullopt);
  // A covariance that is not positive definite names its line.
  try {
    ParsePoseGraph("ODOMETRY 0 1 1 0 0 0.01 0 0 0.01 0 0.01\nLANDMARK 1 7 2 1 0.1 0.5 0.1\n", "bad.txt");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 2);
    EXPECT_NE(std::string(e.what()).find("covariance"), std::string::npos) << e.what();
  }
}

TEST(IsamNoise, VictoriaParkGtsamWhenPresent) {
  const std::string path = testing::PublicDataFile(SLAMBOX_SOURCE_DIR, "landmark/victoria_park/victoria_park_gtsam.txt");
  if (path.empty()) GTEST_SKIP() << "public data absent (../shared/data or $SLAMBOX_DATA)";
  const PoseGraphFile f = ReadPoseGraph(path);
  EXPECT_EQ(f.isam_noise, IsamNoise::kCovariance);
  EXPECT_EQ(f.graph.poses.size(), 6969u);  // the data README: 6969 poses, 151 landmarks
  EXPECT_EQ(f.graph.landmarks.size(), 151u);
  EXPECT_EQ(f.graph.landmark_edges.size(), 3640u);
}

}  // namespace
}  // namespace slambox
