#include "core/kitti_poses.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "core/error.hpp"
#include "core/tum.hpp"

namespace slambox {
namespace {

namespace fs = std::filesystem;

fs::path Temp(const std::string& name) {
  return fs::temp_directory_path() / ("slambox_kitti_" + std::to_string(::getpid()) + "_" + name);
}

std::vector<StampedPose> RandomPoses(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(-100, 100), ang(-M_PI, M_PI);
  std::vector<StampedPose> out;
  for (int i = 0; i < n; ++i) out.push_back({double(i), SE2(pos(rng), pos(rng), ang(rng))});
  out[0].pose = SE2(1, 2, M_PI);   // the wrap point
  out[1].pose = SE2(0, 0, -M_PI);
  return out;
}

TEST(KittiPoses, RoundTripXYExactlyAndYawToOneUlp) {
  const auto poses = RandomPoses(200, 3);
  const fs::path p = Temp("rt.kitti");
  WriteKittiPoses(p.string(), poses);
  const auto back = ReadKittiPoses(p.string());
  ASSERT_EQ(back.size(), poses.size());
  for (size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(back[i].t_s, double(i));
    EXPECT_EQ(back[i].pose.x, poses[i].pose.x);
    EXPECT_EQ(back[i].pose.y, poses[i].pose.y);
    // atan2(sin, cos) of a wrapped angle: the same angle up to rounding, and the wrap maps to the same point.
    EXPECT_NEAR(std::remainder(back[i].pose.theta - poses[i].pose.theta, 2 * M_PI), 0.0, 4e-16) << i;
  }
  fs::remove(p);
}

TEST(KittiPoses, RowsAreTheThreeByFourMatrix) {
  const fs::path p = Temp("rows.kitti");
  WriteKittiPoses(p.string(), {{0.0, SE2(3, -4, M_PI / 2)}});
  std::ifstream in(p);
  double r[12];
  for (double& v : r) in >> v;
  const double expected[12] = {0, -1, 0, 3, 1, 0, 0, -4, 0, 0, 1, 0};
  for (int i = 0; i < 12; ++i) EXPECT_NEAR(r[i], expected[i], 1e-16) << i;
  fs::remove(p);
}

TEST(KittiPoses, TumAndKittiOfTheSamePosesAgree) {
  const auto poses = RandomPoses(50, 9);
  const fs::path tum = Temp("same.tum"), kitti = Temp("same.kitti");
  WriteTum(tum.string(), poses);
  WriteKittiPoses(kitti.string(), poses);
  EXPECT_EQ(DetectTrajectoryFormat(tum.string()), TrajectoryFormat::kTum);
  EXPECT_EQ(DetectTrajectoryFormat(kitti.string()), TrajectoryFormat::kKitti);
  const auto a = ReadTum(tum.string()), b = ReadKittiPoses(kitti.string());
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].pose.x, b[i].pose.x);
    EXPECT_EQ(a[i].pose.y, b[i].pose.y);
    EXPECT_NEAR(std::remainder(a[i].pose.theta - b[i].pose.theta, 2 * M_PI), 0.0, 1e-15);
  }
  fs::remove(tum);
  fs::remove(kitti);
}

TEST(KittiPoses, BadLinesNameTheFileAndLine) {
  const std::pair<std::string, std::string> cases[] = {
      {"1 0 0 0 0 1 0 0 0 0 1\n", "expected 12 numbers"},
      {"1 0 0 0 0 1 0 0 0 0 1 0 7\n", "more than 12 numbers"},
      {"1 0 0 nan 0 1 0 0 0 0 1 0\n", "expected 12 numbers"},  // istream rejects nan
      {"1 0 0 0 0 0 -1 0 0 1 0 0\n", "leaves the x-y plane"},  // KITTI camera frame: rotation about x
      {"1 0 0 0 0 1 0 0 0 0 1 2.5\n", "leaves the x-y plane"},  // z != 0
  };
  const fs::path p = Temp("bad.kitti");
  for (const auto& [line, message] : cases) {
    std::ofstream(p) << "# comment\n1 0 0 0 0 1 0 0 0 0 1 0\n" << line;
    try {
      ReadKittiPoses(p.string());
      ADD_FAILURE() << "no error for " << line;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(message), std::string::npos) << e.what();
      EXPECT_EQ(e.line(), 3) << e.what();
    }
  }
  std::ofstream(p) << "1 2 3\n";
  EXPECT_THROW(DetectTrajectoryFormat(p.string()), InputError);
  std::ofstream(p) << "# only a comment\n";
  EXPECT_THROW(DetectTrajectoryFormat(p.string()), InputError);
  fs::remove(p);
}

}  // namespace
}  // namespace slambox
