// Sweep expansion, stable ids, shards, CSV and summary statistics (no processes run here).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "core/csv.hpp"
#include "app/sweep_spec.hpp"
#include "app/sweep_summary.hpp"
#include "core/error.hpp"
#include "tests/support/slambox_cli.hpp"

namespace slambox {
namespace {

namespace fs = std::filesystem;

std::string WriteTemp(const std::string& name, const std::string& text) {
  static const fs::path dir = testing::FreshTempDir("sweep_spec");
  const fs::path p = dir / name;
  std::ofstream(p) << text;
  return p.string();
}

TEST(SweepSpec, ExpandsCartesianProductInStableOrder) {
  const auto path = WriteTemp("a.yaml",
                              "scenarios: [loop, tunnel]\nalgorithms: [odometry]\nseeds: 3\n"
                              "grid:\n  sensors.lidar.sigma_range_m: [0.01, 0.05]\n  robot.laps: [1, 2]\n");
  const SweepSpec spec = LoadSweepSpec(path);
  const auto runs = ExpandSweep(spec);
  ASSERT_EQ(runs.size(), 2u * 2u * 2u * 3u);
  EXPECT_EQ(runs[0].scenario, "loop");
  EXPECT_EQ(runs[0].sets, (std::vector<std::string>{"sensors.lidar.sigma_range_m=0.01", "robot.laps=1"}));
  EXPECT_EQ(runs[3].sets, (std::vector<std::string>{"sensors.lidar.sigma_range_m=0.01", "robot.laps=2"}));  // last key fastest
  EXPECT_EQ(runs[6].sets[0], "sensors.lidar.sigma_range_m=0.05");
  EXPECT_EQ(runs[12].scenario, "tunnel");
  std::set<std::string> ids;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    EXPECT_EQ(runs[i].index, i);
    EXPECT_EQ(runs[i].seed, i % 3);
    ids.insert(runs[i].id);
  }
  EXPECT_EQ(ids.size(), runs.size()) << "run ids must be unique";
  // Same description => same id, whatever the position in the sweep.
  EXPECT_EQ(RunId("loop", runs[0].sets, 0), runs[0].id);
  EXPECT_NE(RunId("loop", runs[0].sets, 1), runs[0].id);
  EXPECT_EQ(runs[0].id.size(), 16u);
}

TEST(SweepSpec, SeedListAndFixedSets) {
  const auto path = WriteTemp("b.yaml", "scenarios: [loop]\nalgorithms: [all]\nseeds: [4, 9]\nset: {robot.laps: 1}\ntimeout_s: 30\n");
  const SweepSpec spec = LoadSweepSpec(path);
  const auto runs = ExpandSweep(spec);
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[1].seed, 9u);
  EXPECT_EQ(runs[1].sets, (std::vector<std::string>{"robot.laps=1"}));
  EXPECT_DOUBLE_EQ(spec.timeout_s, 30.0);
}

TEST(SweepSpec, PerMetricCheckTolerances) {
  const auto ok = WriteTemp("chk.yaml", "scenarios: [loop]\nalgorithms: [odometry]\nseeds: 1\n"
                                        "check: {anees: {relative: 0.5}, ate_rmse_m: {relative: 0.2, absolute: 0.001}}\n");
  const SweepSpec spec = LoadSweepSpec(ok);
  ASSERT_EQ(spec.check_tolerances.size(), 2u);
  EXPECT_EQ(spec.check_tolerances[1].first, "ate_rmse_m");
  EXPECT_DOUBLE_EQ(spec.check_tolerances[1].second.first, 0.2);
  EXPECT_DOUBLE_EQ(spec.check_tolerances[1].second.second, 0.001);
  for (const char* bad : {"check: {heading_rmse_deg: {relative: 0.1}}\n", "check: {anees: {relativ: 0.1}}\n",
                          "check: {anees: {relative: -1}}\n", "check: [anees]\n"}) {
    const auto path = WriteTemp("bad_chk.yaml", std::string("scenarios: [loop]\nalgorithms: [odometry]\nseeds: 1\n") + bad);
    EXPECT_THROW(LoadSweepSpec(path), InputError) << bad;
  }
}

TEST(SweepSpec, ShardsCoverEveryRunExactlyOnce) {
  const auto path = WriteTemp("c.yaml", "scenarios: [a, b, c]\nalgorithms: [odometry]\nseeds: 7\n");
  const auto runs = ExpandSweep(LoadSweepSpec(path));
  for (std::size_t n : {1u, 2u, 4u, 5u, 30u}) {
    std::vector<int> covered(runs.size(), 0);
    for (std::size_t shard = 0; shard < n; ++shard)
      for (const auto& r : runs)
        if (r.index % n == shard) ++covered[r.index];
    for (int c : covered) EXPECT_EQ(c, 1);
  }
}

TEST(SweepSpec, ErrorsNameFileLineAndFix) {
  struct Case { std::string text, expect; };
  const std::vector<Case> cases = {
      {"scenarios: [loop]\nalgorithms: [odometry]\nseeds: 3\nseedz: 4\n", ":4: unknown key 'seedz'"},
      {"scenarios: [loop]\nalgorithms: [odometry]\n", "missing 'seeds'"},
      {"scenarios: []\nalgorithms: [odometry]\nseeds: 2\n", ":1: 'scenarios' must be a non-empty list"},
      {"scenarios: [loop]\nalgorithms: [odometry]\nseeds: -1\n", ":3: seeds must be 1..100000"},
      {"scenarios: [loop]\nalgorithms: [odometry]\nseeds: [1, 1]\n", "a seed is listed twice"},
      {"scenarios: [loop]\nalgorithms: [odometry]\nseeds: 2\ngrid: {robot.laps: 3}\n", "needs a non-empty list"},
      {"scenarios: [loop]\nalgorithms: [odometry]\nseeds: 2\ntimeout_s: 0\n", "timeout_s must be a positive number"},
      {"scenarios: [loop\n", "not valid YAML"},
  };
  for (const auto& c : cases) {
    const auto path = WriteTemp("bad.yaml", c.text);
    try {
      LoadSweepSpec(path);
      ADD_FAILURE() << "accepted: " << c.text;
    } catch (const InputError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(path), std::string::npos) << msg;
      EXPECT_NE(msg.find(c.expect), std::string::npos) << msg;
      EXPECT_NE(msg.find("fix:"), std::string::npos) << msg;
    }
  }
}

// A name longer than the file system allows (found by fuzz_sweep): std::filesystem's
// throwing queries ended the process with filesystem_error (ENAMETOOLONG); now such a name
// is "not a file": a scenario name, or a relations file that is reported missing.
TEST(SweepSpec, NamesLongerThanTheFileSystemAllowsAreNotFilesNotCrashes) {
  const std::string long_name(1000, 'x');
  const auto spec = LoadSweepSpec(WriteTemp("long_scenario.yaml", "scenarios: [" + long_name +
                                                                      "]\nalgorithms: [odometry]\nseeds: 1\n"));
  ASSERT_EQ(spec.scenarios.size(), 1u);
  EXPECT_EQ(spec.scenarios[0], long_name);
  EXPECT_EQ(ExpandSweep(spec).size(), 1u);
  const auto path = WriteTemp("long_relations.yaml", "scenarios: [loop]\nalgorithms: [odometry]\nseeds: 1\n"
                                                     "relations: {loop: " + long_name + "}\n");
  try {
    LoadSweepSpec(path);
    ADD_FAILURE() << "accepted a relations file that cannot exist";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(path + ":4:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("not found"), std::string::npos) << msg;
  }
}

TEST(Csv, QuotesRoundTrip) {
  const CsvRow row = {"plain", "with,comma", "with \"quote\"", "", "[0.1, 0.2]"};
  const auto rows = ParseCsv(CsvLine(row) + CsvLine(row), "x.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1], row);
  EXPECT_THROW(ParseCsv("a,b\n1\n", "x.csv"), InputError);
  EXPECT_THROW(ParseCsv("a,b\n\"1,2\n", "x.csv"), InputError);
}

}  // namespace
}  // namespace slambox
