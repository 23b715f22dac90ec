// The sweep report end to end through the real binary: every worker draws its run's
// pictures (runs/<id>/pictures/), metrics.json and sweep.json carry each module's baseline
// flag from its registry entry, a user (exec) module can declare itself a baseline, and
// report.html embeds one seed's pictures per scenario with the tables.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/support/slambox_cli.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kBinary = SLAMBOX_BINARY;
const std::string kSource = SLAMBOX_SOURCE_DIR;

TEST(SweepReportCli, WorkersDrawPicturesAndModulesCarryTheirBaselineFlag) {
  const fs::path dir = slambox::testing::FreshTempDir("sweep_report_cli");
  // A user module that declares itself a baseline: the Python dead reckoning example.
  std::ofstream(dir / "my-reference.yaml") << "version: 1\ndescription: a declared baseline\n"
                                           << "command: [/usr/bin/python3, " << kSource
                                           << "/examples/python/dead_reckoning.py]\nneeds: [odometry]\nbaseline: true\n";
  const std::string exec = "exec:" + (dir / "my-reference.yaml").string();
  std::ofstream(dir / "sweep.yaml") << "scenarios: [loop, landmarks]\nalgorithms: [odometry, icp-odometry, ekf-slam, "
                                    << exec << "]\nseeds: 2\nset: {duration_s: 8}\n";
  const auto r = slambox::testing::RunSlambox(kBinary, "sweep " + (dir / "sweep.yaml").string() + " -j 2 -o " +
                                                           (dir / "out").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const json spec = json::parse(slambox::testing::ReadText(dir / "out/sweep.json"));
  EXPECT_EQ(spec["modules"]["odometry"]["baseline"], true);
  EXPECT_EQ(spec["modules"]["icp-odometry"]["baseline"], false);
  EXPECT_EQ(spec["modules"]["exec:my-reference"]["baseline"], true) << spec.dump(1);  // its own name
  EXPECT_EQ(spec["interval"], "auto");
  int runs = 0;
  for (const auto& e : fs::directory_iterator(dir / "out/runs")) {
    ++runs;
    const json m = json::parse(slambox::testing::ReadText(e.path() / "metrics.json"));
    EXPECT_EQ(m["modules"]["odometry"]["baseline"], true);
    EXPECT_EQ(m["modules"]["exec:my-reference"]["baseline"], true) << m["modules"].dump();
    EXPECT_TRUE(fs::exists(e.path() / "pictures/trajectories.png")) << e.path();
    EXPECT_FALSE(fs::exists(e.path() / "figures")) << "workers draw the pictures only";
    // A map per mapping module of the run: ekf-slam on landmarks (icp-odometry keeps no map).
    if (m["scenario"] == "landmarks") {
      EXPECT_TRUE(fs::exists(e.path() / "pictures/map_ekf-slam.png")) << e.path();
    }
  }
  EXPECT_EQ(runs, 4);
  const std::string html = slambox::testing::ReadText(dir / "out/report.html");
  size_t images = 0;
  for (size_t p = 0; (p = html.find("<img ", p)) != std::string::npos; ++p) ++images;
  EXPECT_GE(images, 2u + 1u + 2u) << "two worlds, ekf-slam's map and the box plots";
  EXPECT_NE(html.find("the median of 2 seeds"), std::string::npos);
  // --no-figures: no pictures, and the report (not written) is not needed for results.
  const auto q = slambox::testing::RunSlambox(kBinary, "sweep " + (dir / "sweep.yaml").string() +
                                                           " -j 2 --no-figures -o " + (dir / "plain").string());
  ASSERT_EQ(q.code, 0) << q.output;
  for (const auto& e : fs::directory_iterator(dir / "plain/runs")) EXPECT_FALSE(fs::exists(e.path() / "pictures"));
  EXPECT_EQ(slambox::testing::ReadText(dir / "plain/results.csv"), slambox::testing::ReadText(dir / "out/results.csv"));
  fs::remove_all(dir);
}

}  // namespace
