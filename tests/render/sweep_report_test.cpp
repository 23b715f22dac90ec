// The sweep report: one representative seed per scenario and grid point, its pictures
// drawn from a run in memory, the tables and pictures per scenario in report.html, and
// baselines styled by their ModuleInfo flag, never by their name.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "core/error.hpp"
#include "render/palette.hpp"
#include "render/png_io.hpp"
#include "render/report.hpp"
#include "render/run_pictures.hpp"
#include "render/sweep_folder.hpp"
#include "render/world_layer.hpp"
#include "tests/render/synthetic_run.hpp"
#include "tests/render/synthetic_sweep.hpp"
#include "tests/support/slambox_cli.hpp"

namespace slambox::render {
namespace {

namespace fs = std::filesystem;

ResultRow Row(std::uint64_t seed, const std::string& algo, double ate, const std::string& status = "ok") {
  return {.run_id = "r" + std::to_string(seed), .scenario = "s", .seed = seed, .algorithm = algo, .status = status,
          .grid = {}, .metrics = {{"ate_rmse_m", ate}}};
}

TEST(RepresentativeRun, TheMedianSeedByEachModulesAteRank) {
  // Ranks (0 = best) over seeds 0..4: a: 4 0 1 2 3; b: 4 1 0 3 2 -> sums 8 1 1 5 5.
  // Sorted (1, s1) (1, s2) (5, s3) (5, s4) (8, s0): the median is seed 3.
  std::vector<ResultRow> rows;
  const double a[] = {5, 1, 2, 3, 4}, b[] = {50, 20, 10, 40, 30};
  for (std::uint64_t s = 0; s < 5; ++s) rows.push_back(Row(s, "a", a[s])), rows.push_back(Row(s, "b", b[s]));
  std::vector<const ResultRow*> ptrs;
  for (const auto& r : rows) ptrs.push_back(&r);
  Representative rep = RepresentativeRun(ptrs);
  EXPECT_EQ(rep.seed, 3u);
  EXPECT_EQ(rep.run_id, "r3");
  EXPECT_EQ(rep.seeds, 5);
  // A failed run ranks last whatever its ATE cell says: seed 1 of a fails -> a's ranks
  // 3 4 0 1 2, sums 7 5 0 4 4 -> (0 s2) (4 s3) (4 s4) (5 s1) (7 s0): seed 4.
  rows[2] = Row(1, "a", 0.0, "failed");
  rep = RepresentativeRun(ptrs);
  EXPECT_EQ(rep.seed, 4u);
  EXPECT_TRUE(RepresentativeRun({}).run_id.empty());
}

TEST(RunPictures, DrawnFromTheRunInMemoryPngOnly) {
  const fs::path dir = testing::FreshTempDir("pictures");
  testing::WriteSyntheticRun(dir.string());
  const RunFolder run = ReadRunFolder(dir.string());
  const auto written = RenderRunPictures(run, dir.string());
  // fastslam2's synthetic estimate holds particles only: no map to draw.
  EXPECT_EQ(written, (std::vector<std::string>{"pictures/trajectories", "pictures/map_ekf-slam",
                                               "pictures/map_icp-poseslam"}));
  for (const auto& stem : written) {
    const Image img = ReadPng((dir / (stem + ".png")).string());
    EXPECT_EQ(img.width, 800) << stem;
    EXPECT_FALSE(fs::exists(dir / (stem + ".svg"))) << stem;
  }
  // A converted log (no world, no ground truth): the maps only.
  RunFolder log = run;
  log.world = {};
  log.has_world = false;
  log.groundtruth.clear();
  const fs::path log_dir = dir / "log";
  const auto log_written = RenderRunPictures(log, log_dir.string());
  EXPECT_EQ(std::count(log_written.begin(), log_written.end(), "pictures/trajectories"), 0);
  EXPECT_FALSE(log_written.empty());
  fs::remove_all(dir);
}

TEST(Baseline, StyledByTheModuleFlagNotByTheName) {
  const fs::path dir = testing::FreshTempDir("baseline");
  testing::WriteSyntheticRun(dir.string());
  RunFolder run = ReadRunFolder(dir.string());  // metrics.json's modules: odometry is the baseline
  ASSERT_EQ(run.algorithms.back().name, "odometry");
  EXPECT_TRUE(run.algorithms.back().baseline);
  EXPECT_FALSE(run.algorithms.front().baseline);
  EXPECT_FALSE(AlgorithmStyle(run, run.algorithms.size() - 1).stroke.dash_px.empty());
  // A module called odometry that does not declare itself a baseline is drawn as any
  // other; a user module that declares itself one is dashed and orange.
  run.algorithms.back().baseline = false;
  run.algorithms.front().baseline = true;
  const SeriesStyle named = AlgorithmStyle(run, run.algorithms.size() - 1), flagged = AlgorithmStyle(run, 0);
  EXPECT_TRUE(named.stroke.dash_px.empty()) << "render fell back to the module's name";
  EXPECT_NE(named.stroke.color, color::kOrange) << "render fell back to the module's name";
  EXPECT_FALSE(flagged.stroke.dash_px.empty());
  EXPECT_EQ(flagged.stroke.color, color::kOrange);
  // The same from the files: metrics.json without `modules` (an older run) has no baseline.
  nlohmann::json m = ReadJsonFile((dir / "metrics.json").string());
  m.erase("modules");
  WriteFileAtomic((dir / "metrics.json").string(), m.dump());
  for (const auto& a : ReadRunFolder(dir.string()).algorithms) EXPECT_FALSE(a.baseline) << a.name;
  m["modules"] = {{"odometry", {{"baseline", "yes"}}}};
  WriteFileAtomic((dir / "metrics.json").string(), m.dump());
  EXPECT_THROW(ReadRunFolder(dir.string()), InputError);
  // Sweep figures read the flag from sweep.json.
  const fs::path sweep = dir / "sweep";
  testing::WriteSyntheticSweep(sweep.string());
  nlohmann::json spec = ReadJsonFile((sweep / "sweep.json").string());
  spec["modules"] = {{"icp-poseslam", {{"baseline", true}}}, {"odometry", {{"baseline", false}}}};
  WriteFileAtomic((sweep / "sweep.json").string(), spec.dump());
  const SweepFolder sw = ReadSweepFolder(sweep.string());
  EXPECT_EQ(sw.algorithms, (std::vector<std::string>{"icp-poseslam", "odometry"}));
  EXPECT_EQ(sw.baseline, (std::vector<bool>{true, false}));
  EXPECT_EQ(ModuleColor(sw.baseline, 0), color::kOrange);
  EXPECT_NE(ModuleColor(sw.baseline, 1), color::kOrange);
  fs::remove_all(dir);
}

/// The synthetic sweep with pictures in every run folder (one set drawn, then copied).
void AddPictures(const fs::path& sweep) {
  const fs::path run = sweep / "template_run";
  testing::WriteSyntheticRun(run.string());
  RenderRunPictures(ReadRunFolder(run.string()), run.string());
  for (const auto& r : ReadSweepFolder(sweep.string()).results.rows) {
    const fs::path to = sweep / "runs" / r.run_id / kPicturesDir;
    if (fs::exists(to)) continue;
    fs::create_directories(to);
    fs::copy(run / kPicturesDir, to);
  }
  fs::remove_all(run);
}

TEST(SweepReport, TablesAndPicturesPerScenarioWithContents) {
  const fs::path dir = testing::FreshTempDir("sweep_report");
  testing::WriteSyntheticSweep(dir.string());
  AddPictures(dir);
  WriteReport(dir.string());
  const std::string md = testing::ReadText(dir / "report.md"), html = testing::ReadText(dir / "report.html");
  // Contents, then per scenario its table, its collapsed intervals and its pictures.
  EXPECT_NE(html.find("<a href=\"#loop\">loop</a>"), std::string::npos);
  EXPECT_NE(html.find("<h2 id=\"loop\">loop</h2>"), std::string::npos);
  EXPECT_NE(html.find("<h2 id=\"tunnel\">tunnel</h2>"), std::string::npos);
  EXPECT_NE(html.find("<details><summary>loop: medians and 95 % intervals"), std::string::npos);
  const size_t loop = md.find("## loop"), tunnel = md.find("## tunnel");
  ASSERT_LT(loop, tunnel);
  const std::string loop_part = md.substr(loop, tunnel - loop);
  // 6 grid points, each its representative seed's world and the map of the one sweep
  // module that builds one (the run folders also hold ekf-slam's, which this sweep did not run).
  size_t pictures = 0;
  for (size_t p = 0; (p = loop_part.find("/pictures/", p)) != std::string::npos; ++p) ++pictures;
  EXPECT_EQ(pictures, 6u * 2u) << loop_part;
  EXPECT_EQ(loop_part.find("map_ekf-slam"), std::string::npos);
  EXPECT_NE(loop_part.find("the median of 6 seeds"), std::string::npos);
  EXPECT_NE(loop_part.find("| ATE RMSE [m]"), std::string::npos);
  EXPECT_EQ(loop_part.find("RPE rot"), std::string::npos) << "a column without any value is left out";
  // Self-contained: every picture embedded, no file reference left.
  size_t embedded = 0;
  for (size_t p = 0; (p = html.find("src=\"data:image/png;base64,", p)) != std::string::npos; ++p) ++embedded;
  EXPECT_EQ(embedded, 2u * 6 * 2);
  EXPECT_EQ(html.find("src=\"runs/"), std::string::npos);
  EXPECT_NE(html.find("name=\"viewport\""), std::string::npos);
  fs::remove_all(dir);
}

TEST(SweepReport, SaysSoWhenTheSweepHasNoPictures) {
  const fs::path dir = testing::FreshTempDir("sweep_report_none");
  testing::WriteSyntheticSweep(dir.string());
  WriteReport(dir.string());
  EXPECT_NE(testing::ReadText(dir / "report.md").find("No pictures of this scenario's runs"), std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace slambox::render
