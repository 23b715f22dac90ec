#include "app/simulate_command.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "core/error.hpp"
#include "core/stream_io.hpp"
#include "tests/support/slambox_cli.hpp"

namespace slambox {
namespace {

std::string TempPath(const std::string& name) {
  static const std::filesystem::path dir = testing::FreshTempDir("simulate_cmd");
  return (dir / name).string();
}

TEST(SimulateCommand, WritesAStreamThatReadsBackIdentically) {
  SimulateRequest r{"tunnel", 5, {"duration_s=4", "sensors.lidar.beams=90"}, TempPath("tunnel.stream")};
  const SimulateSummary s = SimulateToFile(r);
  const Stream back = ReadStream(r.output);
  EXPECT_EQ(SerializeStream(back), SerializeStream(s.stream));
  EXPECT_EQ(back.header.seed, 5u);
  EXPECT_EQ(back.header.scenario_name, "tunnel");
  EXPECT_EQ(back.header.duration_s, 4.0);
  EXPECT_EQ(back.header.sensors.lidar->beams, 90);
  EXPECT_NE(s.line.find("4.0 s"), std::string::npos) << s.line;
  EXPECT_NE(s.line.find("scans"), std::string::npos) << s.line;
  // The header carries the resolved scenario: loading it again gives the same stream.
  EXPECT_NE(back.header.scenario_yaml.find("beams: 90"), std::string::npos);
}

TEST(SimulateCommand, RejectsAlgorithmKeysAndStreamInputs) {
  SimulateRequest r{"loop", 0, {"algo.ekf-slam.gate=3"}, TempPath("x.stream")};
  try {
    SimulateToFile(r);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("algo."), std::string::npos);
  }
  const std::string stream = TempPath("small.stream");
  SimulateToFile({"tunnel", 0, {"duration_s=1"}, stream});
  EXPECT_THROW(SimulateToFile({stream, 0, {}, TempPath("y.stream")}), InputError);
  EXPECT_FALSE(std::filesystem::exists(TempPath("y.stream")));
}

}  // namespace
}  // namespace slambox
