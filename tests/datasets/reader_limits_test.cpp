// Limits instead of hangs (core/limits.hpp) in the text readers: a line over 1 MiB is
// refused at its line number (no attempt to tokenize a binary file as text).
#include <gtest/gtest.h>

#include <ctime>
#include <string>

#include "core/error.hpp"
#include "core/limits.hpp"
#include "core/tum.hpp"
#include "datasets/carmen_log.hpp"
#include "datasets/victoria_park.hpp"

namespace slambox {
namespace {

template <class F>
void ExpectLineRefused(F&& parse, const std::string& file, int line) {
  const std::clock_t start = std::clock();  // CPU time: the test machine may be shared
  try {
    parse();
    ADD_FAILURE() << file << ": accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), file);
    EXPECT_EQ(e.line(), line);
    EXPECT_NE(std::string(e.what()).find("over the limit of 1048576 bytes per line"), std::string::npos) << e.what();
  }
  EXPECT_LT(static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC, 1.0);
}

TEST(ReaderLimits, OverlongLinesRefusedAtTheirLine) {
  const std::string long_line(limits::kMaxTextLineBytes + 1, '1');
  ExpectLineRefused([&] { ParseCarmenLog("ODOM 0 0 0 0 0 0 1 host 0\n" + long_line + "\n", "long.log"); }, "long.log", 2);
  ExpectLineRefused([&] { ParseVictoriaPark("1 0 1 1 0 0 0 0 0 0 0 0\n\n" + long_line, "long.txt"); }, "long.txt", 3);
  ExpectLineRefused([&] { ParseTum("0 0 0 0 0 0 0 1\n" + long_line + "\n", "long.tum"); }, "long.tum", 2);
  // Exactly at the limit is a line like any other (here: a malformed one).
  try {
    ParseTum(std::string(limits::kMaxTextLineBytes, '1'), "edge.tum");
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).find("bytes per line"), std::string::npos) << e.what();
  }
}

TEST(ReaderLimits, CarmenPosesAndTimesAreBounded) {
  // Found by fuzz_carmen: a pose coordinate of 1e308 made the odometry increment -inf,
  // and the converted stream could not be read back (tests/fuzz/corpus/carmen/finding-huge-pose.log).
  // And a ROBOTLASER1 angular resolution of 1e306 gave an infinite field of view in the
  // header (finding-huge-resolution.log).
  const std::string scan = "FLASER 3 1 2 3 0 0 0 0 0 0 1.1 host 0\n";
  try {
    ParseCarmenLog("ROBOTLASER1 0 -1.5 3.1 1e306 81.9 0.01 0 3 1 2 3 0 0 0 0 0 0 0 0 0 0 0 0 1.3 host 0\n", "res.log");
    ADD_FAILURE() << "accepted a resolution of 1e306";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 1) << e.what();
    EXPECT_NE(std::string(e.what()).find("out of range"), std::string::npos) << e.what();
  }
  for (const std::string& bad : {"ODOM 1e308 0 0 0 0 0 1.2 host 0\n", "ODOM 0 0 -2e4 0 0 0 1.2 host 0\n",
                                 "ODOM 0 0 0 0 0 0 1e300 host 0\n"}) {
    try {
      ParseCarmenLog("ODOM 0 0 0 0 0 0 1.0 host 0\n" + scan + bad, "bad.log");
      ADD_FAILURE() << "accepted " << bad;
    } catch (const InputError& e) {
      EXPECT_EQ(e.line(), 3) << e.what();
      EXPECT_NE(std::string(e.what()).find("out of range"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace slambox
