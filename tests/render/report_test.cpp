// Sweep figures and reports from synthetic folders: every figure renders, the display
// statistics are right, and report.html embeds the figures and the tables.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "render/figures_run.hpp"
#include "render/figures_sweep.hpp"
#include "render/png_io.hpp"
#include "render/report.hpp"
#include "render/sweep_folder.hpp"
#include "tests/render/synthetic_run.hpp"
#include "tests/render/synthetic_sweep.hpp"

namespace slambox::render {
namespace {

namespace fs = std::filesystem;

std::string TempDir(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("slambox_report_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  return p.string();
}

std::string Slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(SweepFigures, SyntheticSweepRendersEveryFigure) {
  const std::string dir = TempDir("sweep");
  testing::WriteSyntheticSweep(dir);
  const SweepFolder sw = ReadSweepFolder(dir);
  EXPECT_EQ(sw.results.rows.size(), 2u * 3 * 2 * 6 * 2);
  EXPECT_EQ(sw.results.metric_keys, (std::vector<std::string>{"ate_rmse_m", "rpe_trans_rmse_m", "anees"}));
  EXPECT_TRUE(std::isnan(sw.results.rows[1].metrics.at("anees")));  // empty cell = null
  const auto written = RenderSweepFiguresListed(dir);
  EXPECT_EQ(written, (std::vector<std::string>{"figures/box_ate_rmse_m", "figures/box_rpe_trans_rmse_m",
                                               "figures/vs_sensors.lidar.sigma_range_m",
                                               "figures/vs_sensors.odometry.alpha_scale",
                                               "figures/heatmap_icp-poseslam", "figures/heatmap_odometry"}));
  for (const auto& stem : written) {
    const Image img = ReadPng(dir + "/" + stem + ".png");
    size_t ink = 0;
    for (size_t i = 0; i < img.rgb.size(); i += 3) ink += img.rgb[i] < 200 || img.rgb[i + 1] < 200 || img.rgb[i + 2] < 200;
    EXPECT_GT(ink, 3000u) << stem;
  }
  fs::remove_all(dir);
}

TEST(SweepFigures, MalformedCsvNamesTheLine) {
  const std::string dir = TempDir("badcsv");
  testing::WriteSyntheticSweep(dir);
  std::ofstream(dir + "/results.csv", std::ios::app) << "999,loop,0,odometry,ok,0.01\n";
  try {
    ReadSweepFolder(dir);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 2 + 2 * 3 * 2 * 6 * 2 - 1 + 1);
  }
  fs::remove_all(dir);
}

TEST(Report, RunReportEmbedsTablesAndFigures) {
  const std::string dir = TempDir("run");
  testing::WriteSyntheticRun(dir);
  RenderRunFigures(dir);
  WriteReport(dir);
  const std::string md = Slurp(dir + "/report.md"), html = Slurp(dir + "/report.html");
  EXPECT_NE(md.find("| odometry | ok | 2.1 |"), std::string::npos) << md;
  EXPECT_NE(md.find("![trajectories](figures/trajectories.png)"), std::string::npos);
  EXPECT_NE(html.find("<td>odometry</td>"), std::string::npos);
  // Self-contained: the trajectories PNG is embedded byte for byte.
  EXPECT_NE(html.find("data:image/png;base64," + Base64(Slurp(dir + "/figures/trajectories.png"))), std::string::npos);
  EXPECT_EQ(html.find("src=\"figures/"), std::string::npos);
  fs::remove_all(dir);
}

TEST(Report, ALogIsNamedWithoutSeedOrDistance) {
  const std::string dir = TempDir("logrun");
  testing::WriteSyntheticRun(dir);
  WriteReport(dir);
  EXPECT_NE(Slurp(dir + "/report.md").find("Scenario **synthetic**, seed "), std::string::npos);
  // As `run` writes a converted log's metrics.json: no seed to show, no true path length.
  nlohmann::json m = nlohmann::json::parse(Slurp(dir + "/metrics.json"));
  m["converted_log"] = true;
  m["distance_m"] = nullptr;
  std::ofstream(dir + "/metrics.json") << m.dump();
  WriteReport(dir);
  const std::string md = Slurp(dir + "/report.md");
  EXPECT_NE(md.find("Log **synthetic**, duration "), std::string::npos) << md.substr(0, 300);
  EXPECT_EQ(md.find("seed"), std::string::npos) << md.substr(0, 300);
  EXPECT_EQ(md.find("distance travelled"), std::string::npos) << md.substr(0, 300);
  fs::remove_all(dir);
}

TEST(Report, SweepReportHasTheSummaryTables) {
  const std::string dir = TempDir("sweeprep");
  testing::WriteSyntheticSweep(dir);
  WriteReport(dir);
  const std::string html = Slurp(dir + "/report.html");
  // The tables summary.md has (eval/summary_tables), from results.csv, one per scenario.
  EXPECT_NE(html.find("<h2 id=\"loop\">loop</h2>"), std::string::npos);
  EXPECT_NE(html.find("<th>ATE RMSE [m]</th>"), std::string::npos);
  EXPECT_NE(html.find("<td><b>"), std::string::npos);  // the best mean
  EXPECT_THROW(WriteReport(TempDir("nothing")), InputError);
  fs::remove_all(dir);
}

TEST(Report, Base64MatchesRfc4648Vectors) {
  EXPECT_EQ(Base64(""), "");
  EXPECT_EQ(Base64("f"), "Zg==");
  EXPECT_EQ(Base64("fo"), "Zm8=");
  EXPECT_EQ(Base64("foobar"), "Zm9vYmFy");
}

TEST(Frames, NumberedFramesAreWritten) {
  const std::string dir = TempDir("frames");
  testing::WriteSyntheticRun(dir);
  EXPECT_EQ(RenderRunFrames(dir, 3), 3);
  for (const char* f : {"frame_00000.png", "frame_00001.png", "frame_00002.png"})
    EXPECT_TRUE(fs::exists(fs::path(dir) / "frames" / f)) << f;
  // Later frames show more of the paths.
  const Image a = ReadPng(dir + "/frames/frame_00000.png"), c = ReadPng(dir + "/frames/frame_00002.png");
  EXPECT_EQ(a.width, c.width);
  EXPECT_NE(a.rgb, c.rgb);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace slambox::render
