// Limits instead of hangs (core/limits.hpp) for sweep files: the number of runs and the
// file size are refused before anything is expanded, in well under 1 s of CPU time.
#include <gtest/gtest.h>

#include <ctime>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "app/sweep_spec.hpp"
#include "core/error.hpp"
#include "core/limits.hpp"

namespace slambox {
namespace {

std::string ErrorOf(const std::string& text) {
  const std::clock_t start = std::clock();  // CPU time: the test machine may be shared
  std::string what;
  try {
    ParseSweepSpec(text, "big-sweep.yaml");
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "big-sweep.yaml");
    what = e.what();
  }
  EXPECT_LT(static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC, 1.0);
  return what;
}

TEST(SweepLimits, TooManyRunsRefused) {
  // 100000 seeds x 3 x 4 grid values = 1.2e6 runs > 1e6.
  const std::string e = ErrorOf(
      "scenarios: [loop]\nalgorithms: [odometry]\nseeds: 100000\ngrid: {robot.laps: [1, 2, 3], duration_s: [1, 2, 3, 4]}\n");
  EXPECT_NE(e.find("the sweep asks for 1200000"), std::string::npos) << e;
  EXPECT_NE(e.find("over the limit of 1000000"), std::string::npos) << e;
  // Exactly at the limit is accepted (it is not expanded here).
  EXPECT_NO_THROW(ParseSweepSpec("scenarios: [loop]\nalgorithms: [odometry]\nseeds: 100000\ngrid: {robot.laps: "
                                 "[1, 2, 3, 4, 5, 6, 7, 8, 9, 10]}\n",
                                 "ok.yaml"));
}

TEST(SweepLimits, HugeFileRefusedUnread) {
  const auto path = std::filesystem::temp_directory_path() / ("slambox_big_sweep_" + std::to_string(getpid()) + ".yaml");
  std::ofstream(path) << "scenarios: [loop]\nalgorithms: [odometry]\nseeds: 1\n# "
                      << std::string(limits::kMaxYamlFileBytes, 'x') << "\n";
  try {
    LoadSweepSpec(path.string());
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("over the limit of 1048576"), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace slambox
