// Figures of a converted real log (no world, no ground truth): the region shown fits the
// map (walls lie beyond the path), and titles name the log without a meaningless seed.
#include <gtest/gtest.h>

#include "render/figures_run_parts.hpp"
#include "render/run_folder.hpp"
#include "render/world_layer.hpp"

namespace slambox::render {
namespace {

RunFolder LogRun() {
  RunFolder run;
  run.scenario = "intel.clf.bz2";
  run.converted_log = true;
  AlgorithmResult a;
  a.name = "icp-poseslam";
  a.trajectory = {{0.0, SE2(0, 0, 0)}, {1.0, SE2(2, 1, 0)}};
  Estimate e;
  e.map_points = {{-3.0, 4.0}, {5.0, -2.0}};
  OccupancyGrid g;
  g.origin_m = {10.0, 10.0};
  g.resolution_m = 1.0;
  g.width = g.height = 2;
  g.cells = {-1, 0, 0, 100};  // only cell (1, 1) is occupied: centre (11.5, 11.5)
  e.grid = g;
  a.estimate = e;
  run.algorithms.push_back(a);
  return run;
}

TEST(LogFigures, ExtentCoversMapPointsAndOccupiedCells) {
  const RunFolder run = LogRun();
  const auto [lo, hi] = RunExtent(run);
  EXPECT_DOUBLE_EQ(lo.x(), -3.0);
  EXPECT_DOUBLE_EQ(lo.y(), -2.0);
  EXPECT_DOUBLE_EQ(hi.x(), 11.5);
  EXPECT_DOUBLE_EQ(hi.y(), 11.5);
  const auto [lo1, hi1] = RunExtent(run, 0);
  EXPECT_EQ(lo1, lo);
  EXPECT_EQ(hi1, hi);
}

TEST(LogFigures, TitleNamesTheLogWithoutASeed) {
  RunFolder run = LogRun();
  EXPECT_EQ(RunTitleSuffix(run), " \u2014 intel.clf.bz2");
  run.groundtruth = {{0.0, SE2()}};  // a converted graph's ground truth: still no seed
  EXPECT_EQ(RunTitleSuffix(run), " \u2014 intel.clf.bz2");
  run.converted_log = false;
  run.seed = 3;
  run.scenario = "loop";
  EXPECT_EQ(RunTitleSuffix(run), " \u2014 loop, seed 3");
}

// The sweep draws a run's pictures from the stream in memory: its titles must be those of
// the run folder read back, so a converted log shows no seed there either.
TEST(LogFigures, PicturesOfAStreamKnowItIsALog) {
  Stream log;
  log.header.scenario_name = "intel.clf.bz2";
  log.header.scenario_yaml = std::string(kConvertedLogYamlPrefix) + "the CARMEN log intel.clf.bz2 (no ground truth)\n";
  const RunFolder from_log = RunFolderOfStream(log, "/tmp/x");
  EXPECT_TRUE(from_log.converted_log);
  EXPECT_FALSE(from_log.has_world);
  EXPECT_EQ(RunTitleSuffix(from_log), " \u2014 intel.clf.bz2");
  Stream simulated;
  simulated.header.scenario_name = "loop";
  simulated.header.scenario_yaml = "version: 1\nname: loop\n";
  simulated.header.seed = 3;
  simulated.groundtruth = {{0.0, SE2()}};
  const RunFolder from_sim = RunFolderOfStream(simulated, "/tmp/y");
  EXPECT_FALSE(from_sim.converted_log);
  EXPECT_EQ(from_sim.groundtruth.size(), 1u);
  EXPECT_EQ(RunTitleSuffix(from_sim), " \u2014 loop, seed 3");
}

}  // namespace
}  // namespace slambox::render
