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

}  // namespace
}  // namespace slambox
