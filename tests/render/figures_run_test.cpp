// A synthetic run folder renders every figure; each is a non-trivial picture, and the
// renderer is deterministic end to end.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <set>
#include <fstream>
#include <sstream>

#include "render/figures_run.hpp"
#include "core/error.hpp"
#include "render/png_io.hpp"
#include "tests/render/synthetic_run.hpp"

namespace slambox::render {
namespace {

namespace fs = std::filesystem;

std::string TempDir(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("slambox_render_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(p);
  return p.string();
}

std::string Slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(RunFigures, SyntheticRunRendersEveryFigure) {
  const std::string dir = TempDir("run");
  testing::WriteSyntheticRun(dir);
  const std::vector<std::string> written = RenderRunFiguresListed(dir);
  const std::vector<std::string> expected{
      "figures/trajectories",        "figures/error_distance",       "figures/nees",
      "figures/map_ekf-slam",        "figures/uncertainty_ekf-slam", "figures/uncertainty_fastslam2",
      "figures/particles_fastslam2", "figures/map_icp-poseslam",     "figures/pose_graph_icp-poseslam",
      "figures/uncertainty_odometry"};
  EXPECT_EQ(written, expected);
  for (const auto& stem : written) {
    const Image img = ReadPng(dir + "/" + stem + ".png");
    // Non-trivial: many non-white pixels and several distinct colours.
    size_t ink = 0;
    std::set<int> colours;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const auto* p = img.At(x, y);
        ink += p[0] < 200 || p[1] < 200 || p[2] < 200;
        colours.insert((p[0] >> 4) << 8 | (p[1] >> 4) << 4 | (p[2] >> 4));
      }
    EXPECT_GT(ink, 5000u) << stem;
    EXPECT_GT(colours.size(), 20u) << stem;
    const std::string svg = Slurp(dir + "/" + stem + ".svg");
    EXPECT_NE(svg.find("<svg"), std::string::npos) << stem;
    EXPECT_NE(svg.find("</svg>"), std::string::npos) << stem;
  }
  fs::remove_all(dir);
}

TEST(RunFigures, RenderingIsBitIdentical) {
  const std::string a = TempDir("det_a"), b = TempDir("det_b");
  testing::WriteSyntheticRun(a);
  testing::WriteSyntheticRun(b);
  RenderRunFigures(a);
  RenderRunFigures(b);
  for (const char* stem : {"trajectories", "error_distance", "pose_graph_icp-poseslam"}) {
    EXPECT_EQ(Slurp(a + "/figures/" + stem + ".png"), Slurp(b + "/figures/" + stem + ".png")) << stem;
    EXPECT_EQ(Slurp(a + "/figures/" + stem + ".svg"), Slurp(b + "/figures/" + stem + ".svg")) << stem;
  }
  fs::remove_all(a);
  fs::remove_all(b);
}

TEST(RunFigures, MissingSeriesAndEstimatesAreSkipped) {
  const std::string dir = TempDir("sparse");
  testing::WriteSyntheticRun(dir, 3, /*with_series=*/false);
  fs::remove_all(fs::path(dir) / "estimates");
  const std::vector<std::string> written = RenderRunFiguresListed(dir);
  EXPECT_EQ(written, std::vector<std::string>{"figures/trajectories"});
  fs::remove_all(dir);
}

TEST(RunFigures, BadFolderIsAnInputError) {
  const std::string dir = TempDir("bad");
  fs::create_directories(dir);
  EXPECT_THROW(RenderRunFigures(dir), InputError);
  std::ofstream(dir + "/metrics.json") << "{\"algorithms\": {\n  \"a\": [1, 2,\n}";
  try {
    RenderRunFigures(dir);
    FAIL() << "no error for malformed metrics.json";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_NE(std::string(e.what()).find("metrics.json"), std::string::npos);
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace slambox::render
