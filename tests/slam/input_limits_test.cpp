// Limits instead of hangs (core/limits.hpp) in slam/: particle counts, grid cells and
// pose-graph line lengths are refused with a clear message, in well under 1 s of CPU time.
#include <gtest/gtest.h>

#include <ctime>
#include <string>

#include "core/error.hpp"
#include "core/limits.hpp"
#include "slam/fastslam.hpp"
#include "slam/g2o_io.hpp"
#include "slam/likelihood_field.hpp"
#include "slam/mcl.hpp"

namespace slambox {
namespace {

template <class F>
std::string ErrorWithin1s(F&& f) {
  const std::clock_t start = std::clock();  // CPU time: the test machine may be shared
  std::string what;
  try {
    f();
  } catch (const InputError& e) {
    what = e.what();
  }
  EXPECT_LT(static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC, 1.0);
  return what;
}

TEST(InputLimits, TooManyParticlesRefused) {
  MclConfig mcl;
  mcl.particles = limits::kMaxParticles + 1;
  const std::string a = ErrorWithin1s([&] { Mcl m(mcl); });
  EXPECT_NE(a.find("--set algo.mcl.particles"), std::string::npos) << a;
  EXPECT_NE(a.find("1 .. 1000000"), std::string::npos) << a;
  FastSlamConfig fs;
  fs.particles = 2'000'000'000;
  const std::string b = ErrorWithin1s([&] { FastSlam1 f(fs); });
  EXPECT_NE(b.find("--set algo.fastslam1.particles"), std::string::npos) << b;
  EXPECT_NE(b.find("needs 1 .. 1000000 particles, got 2000000000"), std::string::npos) << b;
}

TEST(InputLimits, HugeDistanceGridRefused) {
  // Two wall points 100 km apart at 5 cm: 4e12 cells.
  const std::string e = ErrorWithin1s([] { MakeDistanceGrid({{0, 0}, {1e5, 1e5}}, 0.05, 1.0, 1.0); });
  EXPECT_NE(e.find("exceeds the limit of 200000000 cells"), std::string::npos) << e;
  EXPECT_NE(e.find("grid_resolution_m"), std::string::npos) << e;
}

TEST(InputLimits, OverlongGraphLineRefusedAtItsLine) {
  const std::string text = "VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 1 0 0 " + std::string(limits::kMaxTextLineBytes, '7') + "\n";
  try {
    ParsePoseGraph(text, "long.g2o");
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "long.g2o");
    EXPECT_EQ(e.line(), 2);
    EXPECT_NE(std::string(e.what()).find("over the limit of 1048576 bytes per line"), std::string::npos) << e.what();
  }
}

TEST(InputLimits, GraphAnglesAndPositionsAreBounded) {
  // Found by fuzz_pose_graph: theta = 2.1e16 rad wrapped to -4 (no precision left), so the
  // written graph read back differently (tests/fuzz/corpus/pose_graph/finding-huge-angle.g2o).
  for (const std::string& bad : {"VERTEX_SE2 5 2 1 21474836471464489\n", "VERTEX_SE2 5 1e6 1 0\n",
                                 "EDGE_SE2 0 5 1 0 1e5 1 0 0 1 0 1\n"}) {
    try {
      ParsePoseGraph("VERTEX_SE2 0 0 0 0\n" + bad, "bad.g2o");
      ADD_FAILURE() << "accepted " << bad;
    } catch (const InputError& e) {
      EXPECT_EQ(e.line(), 2) << e.what();
      EXPECT_NE(std::string(e.what()).find("is out of range for"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace slambox
