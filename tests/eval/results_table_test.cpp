// results.csv: one writer, one reader (used by the summary, --merge, --check and the sweep
// figures), cells grouped by one key type.
#include "eval/results_table.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "tests/support/slambox_cli.hpp"

namespace slambox {
namespace {

namespace fs = std::filesystem;

std::string WriteTemp(const std::string& name, const std::string& text) {
  static const fs::path dir = testing::FreshTempDir("results");
  const fs::path p = dir / name;
  std::ofstream(p, std::ios::binary) << text;
  return p.string();
}

TEST(ResultsTable, WriteThenReadGivesTheSameTable) {
  ResultsTable t;
  t.grid_keys = {"sensors.lidar.sigma_range_m", "algo.icp-poseslam.loop_kernel"};
  t.metric_keys = {"ate_rmse_m", "anees"};
  t.rows.push_back({.run_id = "a1", .scenario = "loop", .seed = 3, .algorithm = "odometry", .status = "ok",
                    .grid = {{"sensors.lidar.sigma_range_m", "0.01"}, {"algo.icp-poseslam.loop_kernel", "dcs, Φ=1"}},
                    .metrics = {{"ate_rmse_m", AsWritten(1.0 / 3.0)}, {"anees", NAN}}});
  const std::string csv = ResultsCsv(t);
  EXPECT_NE(csv.find("0.333333333,"), std::string::npos) << csv;  // 9 significant digits
  EXPECT_NE(csv.find("\"dcs, Φ=1\""), std::string::npos) << csv;   // quoted: it has a comma
  const ResultsTable back = ReadResultsCsv(WriteTemp("rt.csv", csv));
  EXPECT_EQ(back.grid_keys, t.grid_keys);
  EXPECT_EQ(back.metric_keys, t.metric_keys);
  ASSERT_EQ(back.rows.size(), 1u);
  EXPECT_EQ(back.rows[0].grid, t.rows[0].grid);
  EXPECT_EQ(back.rows[0].seed, 3u);
  EXPECT_EQ(back.rows[0].metrics.at("ate_rmse_m"), t.rows[0].metrics.at("ate_rmse_m"));  // AsWritten: exact
  EXPECT_TRUE(std::isnan(back.rows[0].metrics.at("anees")));
  EXPECT_EQ(ResultsCsv(back), csv);
  EXPECT_EQ(AsWritten(AsWritten(0.1 + 0.2)), AsWritten(0.1 + 0.2));
}

TEST(ResultsTable, CellKeyGroupsEverythingButTheSeed) {
  ResultRow a;
  a.scenario = "loop";
  a.algorithm = "odometry";
  a.grid = {{"robot.laps", "1"}};
  ResultRow b = a;
  b.seed = 7;
  EXPECT_EQ(CellOf(a), CellOf(b));
  b.grid[0].second = "2";
  EXPECT_LT(CellOf(a), CellOf(b));
  EXPECT_EQ(CellOf(a).Text(), "loop | robot.laps=1 | odometry");
  ASSERT_NE(GridValue(a, "robot.laps"), nullptr);
  EXPECT_EQ(*GridValue(a, "robot.laps"), "1");
  EXPECT_EQ(GridValue(a, "robot.speed"), nullptr);
}

TEST(ResultsTable, BadFilesNameTheFileAndTheLine) {
  auto line_of = [](const std::string& path) {
    try {
      ReadResultsCsv(path);
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      return e.line();
    }
    ADD_FAILURE() << "no error for " << path;
    return -1;
  };
  const std::string header = "run_id,scenario,seed,algorithm,status,ate_rmse_m\n";
  EXPECT_EQ(line_of(WriteTemp("none.csv", "") + ".missing"), 0);
  EXPECT_EQ(line_of(WriteTemp("empty.csv", "")), 1);
  EXPECT_EQ(line_of(WriteTemp("header.csv", "scenario,run_id\nloop,a\n")), 1);
  EXPECT_EQ(line_of(WriteTemp("cells.csv", header + "a,loop,0,odometry,ok,1\nb,loop,1,odometry,ok\n")), 3);
  EXPECT_EQ(line_of(WriteTemp("number.csv", header + "a,loop,0,odometry,ok,1\nb,loop,1,odometry,ok,1.5x\n")), 3);
  EXPECT_EQ(line_of(WriteTemp("seed.csv", header + "a,loop,zero,odometry,ok,1\n")), 2);
}

}  // namespace
}  // namespace slambox
