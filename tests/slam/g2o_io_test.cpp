// g2o / TORO reading and writing: round trip bit-exact, id mapping, FIX, TORO's
// information order, and InputErrors naming the line for every kind of bad input.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <tuple>
#include <unistd.h>

#include "core/error.hpp"
#include "slam/g2o_io.hpp"
#include "tests/slam/pose_graph_test_support.hpp"

namespace slambox {
namespace {

std::string TempDir() {
  const auto dir = std::filesystem::temp_directory_path() / ("slambox_g2o_io_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir.string();
}

bool BitEqual(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(G2oIo, RoundTripIsBitExact) {
  testing::SyntheticGraph s = testing::MakeSquareGraph({.laps = 2, .sigma_xy_m = 0.1, .sigma_theta_rad = 0.05});
  s.graph.poses = testing::Perturbed(s.truth, 0, 0.123456789, 0.0987654321, 4);
  s.graph.edges[0].information(0, 1) = s.graph.edges[0].information(1, 0) = 1.0 / 3.0;
  s.graph.anchor = 3;
  const std::vector<int> ids = [&] {
    std::vector<int> v;
    for (size_t i = 0; i < s.graph.poses.size(); ++i) v.push_back(static_cast<int>(10 + 7 * i));
    return v;
  }();
  const std::string path = TempDir() + "/round_trip.g2o";
  WritePoseGraph(path, s.graph, ids);
  const PoseGraphFile back = ReadPoseGraph(path);
  EXPECT_TRUE(back.has_initial_guess);
  EXPECT_EQ(back.vertex_ids, ids);
  EXPECT_EQ(back.graph.anchor, 3);
  ASSERT_EQ(back.graph.poses.size(), s.graph.poses.size());
  for (size_t i = 0; i < s.graph.poses.size(); ++i) {
    EXPECT_TRUE(BitEqual(back.graph.poses[i].x, s.graph.poses[i].x)) << i;
    EXPECT_TRUE(BitEqual(back.graph.poses[i].y, s.graph.poses[i].y)) << i;
    EXPECT_TRUE(BitEqual(back.graph.poses[i].theta, s.graph.poses[i].theta)) << i;
  }
  ASSERT_EQ(back.graph.edges.size(), s.graph.edges.size());
  for (size_t k = 0; k < s.graph.edges.size(); ++k) {
    const PoseGraphEdge &a = s.graph.edges[k], &b = back.graph.edges[k];
    EXPECT_EQ(a.from, b.from);
    EXPECT_EQ(a.to, b.to);
    EXPECT_EQ(a.loop_closure, b.loop_closure);
    EXPECT_TRUE(BitEqual(a.T_from_to.x, b.T_from_to.x) && BitEqual(a.T_from_to.theta, b.T_from_to.theta));
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) EXPECT_TRUE(BitEqual(a.information(r, c), b.information(r, c)));
  }
  EXPECT_EQ(FormatPoseGraph(back.graph, back.vertex_ids), FormatPoseGraph(s.graph, ids));
  std::filesystem::remove_all(std::filesystem::path(path).parent_path());
}

TEST(G2oIo, MapsSparseIdsFixAndCommentsAndFlagsLoopClosures) {
  const PoseGraphFile f = ParsePoseGraph(
      "# a comment\n"
      "VERTEX_SE2 40 2 0 0\n"
      "VERTEX_SE2 5 0 0 0\n"
      "\n"
      "VERTEX_SE2 17 1 0 0.5\n"
      "FIX 17\n"
      "EDGE_SE2 5 17 1 0 0.5 10 1 2 20 3 30\n"
      "EDGE_SE2 17 40 1 0 -0.5 10 0 0 10 0 10\n"
      "EDGE_SE2 5 40 2 0 0 10 0 0 10 0 10\n",
      "mem.g2o");
  EXPECT_EQ(f.vertex_ids, (std::vector<int>{5, 17, 40}));
  EXPECT_EQ(f.graph.anchor, 1);
  EXPECT_EQ(f.fixed, (std::vector<int>{1}));
  ASSERT_EQ(f.graph.edges.size(), 3u);
  EXPECT_EQ(f.graph.edges[0].from, 0);
  EXPECT_EQ(f.graph.edges[0].to, 1);
  EXPECT_FALSE(f.graph.edges[0].loop_closure);
  EXPECT_TRUE(f.graph.edges[2].loop_closure);
  Eigen::Matrix3d I;
  I << 10, 1, 2, 1, 20, 3, 2, 3, 30;  // upper triangle I11 I12 I13 I22 I23 I33, mirrored
  EXPECT_EQ(f.graph.edges[0].information, I);
  EXPECT_DOUBLE_EQ(f.graph.poses[1].theta, 0.5);
}

TEST(G2oIo, ReadsToroOrderingAndEdgesOnlyFiles) {
  // TORO: inf_ff inf_fs inf_ss inf_rr inf_fr inf_sr = xx xy yy tt xt yt.
  const PoseGraphFile f = ParsePoseGraph("EDGE2 0 1 1 0 0 10 1 20 30 2 3\nEDGE2 1 2 1 0 0 10 0 10 10 0 0\n", "t.graph");
  EXPECT_FALSE(f.has_initial_guess);
  ASSERT_EQ(f.graph.poses.size(), 3u);
  Eigen::Matrix3d I;
  I << 10, 1, 2, 1, 20, 3, 2, 3, 30;
  EXPECT_EQ(f.graph.edges[0].information, I);
  EXPECT_EQ(f.graph.anchor, 0);
}

TEST(G2oIo, ReadsIsamSquareRootInformation) {
  // R = [[2, 1, 0], [0, 3, 0.5], [0, 0, 4]] -> Omega = R^T R; EDGE2 in an iSAM file is iSAM too.
  const PoseGraphFile f = ParsePoseGraph("ODOMETRY 0 1 1 0 0 2 1 0 3 0.5 4\nEDGE2 1 0 -1 0 0 2 1 0 3 0.5 4\n", "m.txt");
  Eigen::Matrix3d R;
  R << 2, 1, 0, 0, 3, 0.5, 0, 0, 4;
  ASSERT_EQ(f.graph.edges.size(), 2u);
  EXPECT_TRUE(f.graph.edges[0].information.isApprox(R.transpose() * R, 1e-15));
  EXPECT_TRUE(f.graph.edges[1].information.isApprox(R.transpose() * R, 1e-15));
}

void ExpectInputError(const std::string& text, int line, const std::string& needle) {
  try {
    ParsePoseGraph(text, "bad.g2o");
    ADD_FAILURE() << "no InputError for:\n" << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "bad.g2o");
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("fix:"), std::string::npos) << e.what();
  }
}

TEST(G2oIo, MalformedInputNamesTheLine) {
  const std::string v = "VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 1 0 0\n";
  ExpectInputError(v + "EDGE_SE2 0 1 1 0 0 1 0 0 1 0\n", 3, "has 10 values, expected 11");
  ExpectInputError(v + "EDGE_SE2 0 1 1 0 nan 1 0 0 1 0 1\n", 3, "is nan");
  ExpectInputError(v + "EDGE_SE2 0 1 1 0 0x 1 0 0 1 0 1\n", 3, "not a number");
  ExpectInputError(v + "EDGE_SE2 0 7 1 0 0 1 0 0 1 0 1\n", 3, "vertex 7");
  ExpectInputError(v + "EDGE_SE2 0 1 1 0 0 1 0 0 -1 0 1\n", 3, "not positive definite");
  ExpectInputError(v + "EDGE_SE2 -1 1 1 0 0 1 0 0 1 0 1\n", 3, "not a non-negative integer");
  ExpectInputError(v + "VERTEX_XY 2 1 1\n", 3, "unknown tag 'VERTEX_XY'");
  ExpectInputError(v + "VERTEX_SE2 1 0 0 0\n", 3, "defined twice");
  ExpectInputError(v + "FIX 9\n", 3, "FIX names vertex 9");
  ExpectInputError("VERTEX_SE2 0 0 inf 0\n", 1, "is inf");
  ExpectInputError("\n# nothing\n", 0, "no vertices or edges");
}

TEST(G2oIo, MissingFileAndUnwritablePathFailCleanly) {
  EXPECT_THROW(ReadPoseGraph("/nonexistent/graph.g2o"), InputError);
  const std::string dir = TempDir();
  const std::string blocker = dir + "/blocker";
  std::ofstream(blocker) << "x";
  testing::SyntheticGraph s = testing::MakeSquareGraph({.laps = 1});
  EXPECT_ANY_THROW(WritePoseGraph(blocker + "/out.g2o", s.graph));  // parent is a file
  EXPECT_FALSE(std::filesystem::exists(blocker + "/out.g2o"));
  std::filesystem::remove_all(dir);
}

// Pose / edge counts of the public graphs as listed in the data README.
TEST(G2oIo, ReadsThePublicGraphs) {
  const std::vector<std::tuple<std::string, size_t, size_t, bool>> graphs = {
      {"posegraph/intel.g2o", 1728, 2512, true},      {"posegraph/CSAIL.g2o", 1045, 1172, false},
      {"posegraph/manhattan.g2o", 3500, 5453, false}, {"posegraph/city10000.g2o", 10000, 20687, true},
      {"posegraph/w10000_toro.graph", 10000, 64311, true},
      {"posegraph/manhattanOlson3500_isam.txt", 3500, 5598, false}};
  int read = 0;
  for (const auto& [relative, poses, edges, has_guess] : graphs) {
    const std::string path = testing::PublicDataFile(SLAMBOX_SOURCE_DIR, relative);
    if (path.empty()) continue;
    const PoseGraphFile f = ReadPoseGraph(path);
    EXPECT_EQ(f.graph.poses.size(), poses) << relative;
    EXPECT_EQ(f.graph.edges.size(), edges) << relative;
    EXPECT_EQ(f.has_initial_guess, has_guess) << relative;
    ++read;
  }
  if (read == 0) GTEST_SKIP() << "no public pose graphs found (posegraph/ in the data folder); set SLAMBOX_DATA";
}

}  // namespace
}  // namespace slambox
