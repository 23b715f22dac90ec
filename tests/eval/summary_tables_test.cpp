// summary.md's tables: mean ± std to 3 significant digits, `k/n ok` for failed runs, the
// best mean in bold, empty columns left out, the collapsed medians/intervals table, and
// a width that reads as plain text.
#include "eval/summary_tables.hpp"

#include <gtest/gtest.h>

#include <sstream>

namespace slambox {
namespace {

TEST(SummaryTables, MeanAndStdToThreeSignificantDigits) {
  EXPECT_EQ(FormatMeanStd(3.4912, 1.2), "3.49 ± 1.20");
  EXPECT_EQ(FormatMeanStd(0.006284, 6.6e-05), "0.00628 ± 0.00007");
  EXPECT_EQ(FormatMeanStd(39.14, 12.34), "39.1 ± 12.3");
  EXPECT_EQ(FormatMeanStd(1234.6, 56.7), "1235 ± 57");  // never an exponent
  EXPECT_EQ(FormatMeanStd(0.5, 0.0), "0.500 ± 0.000");
  EXPECT_EQ(FormatMeanStd(0.5, 1e-6), "0.500 ± 1e-06");  // would show as 0.000
  EXPECT_EQ(FormatMeanStd(0.0, 0.0), "0 ± 0");
}

ResultRow Row(const std::string& algo, std::uint64_t seed, const std::string& status, double ate, double anees) {
  return {.run_id = std::to_string(seed), .scenario = "loop", .seed = seed, .algorithm = algo, .status = status,
          .grid = {}, .metrics = {{"ate_rmse_m", ate}, {"anees", anees}, {"rpe_rot_rmse_deg", NAN}}};
}

TEST(SummaryTables, OneScenarioTable) {
  ResultsTable t;
  t.metric_keys = {"ate_rmse_m", "anees", "rpe_rot_rmse_deg"};
  for (std::uint64_t s = 0; s < 3; ++s) {
    t.rows.push_back(Row("odometry", s, "ok", 3.0 + s, NAN));
    t.rows.push_back(Row("icp-poseslam", s, s == 2 ? "diverged" : "ok", 0.01 * (1 + s), 1.0));
    t.rows.push_back(Row("ekf-slam", s, "failed", NAN, NAN));
  }
  t.rows.push_back({.run_id = "9", .scenario = "tunnel", .seed = 0, .algorithm = "odometry", .status = "ok",
                    .grid = {}, .metrics = {{"ate_rmse_m", 1.0}}});
  const std::string md = ScenarioSummary(t, "loop", IntervalMethod::kAuto);
  EXPECT_EQ(md.find("tunnel"), std::string::npos);
  // Rows in order of appearance; an empty column (RPE rot) left out, no parameters column.
  // Every column padded to its widest cell, so the file reads as plain text.
  EXPECT_NE(md.find("| algorithm    | ATE RMSE [m]                 | ANEES                |\n"
                    "|--------------|------------------------------|----------------------|\n"), std::string::npos) << md;
  EXPECT_EQ(md.find("RPE rot"), std::string::npos);
  EXPECT_EQ(md.find("parameters"), std::string::npos);
  EXPECT_NE(md.find("| odometry     | 4.00 ± 1.00                  | –                    |"), std::string::npos) << md;
  // 2/3 ok where a run diverged (mean of the ok runs), bold as the best mean; all failed.
  EXPECT_NE(md.find("| icp-poseslam | **0.0150 ± 0.0071 (2/3 ok)** | 1.00 ± 0.00 (2/3 ok) |"), std::string::npos) << md;
  EXPECT_NE(md.find("| ekf-slam     | 0/3 ok                       | 0/3 ok               |"), std::string::npos) << md;
  // The collapsed table: medians and the bootstrap interval (3 seeds: the range).
  EXPECT_NE(md.find("<details><summary>loop: medians and 95 % intervals of the mean (percentile bootstrap)"),
            std::string::npos) << md;
  EXPECT_NE(md.find("| odometry     | ATE RMSE [m] | 3   | 4.00   | 3.00–5.00 "), std::string::npos) << md;
  EXPECT_NE(md.find("| icp-poseslam | ATE RMSE [m] | 2   | 0.0150 | 0.0100–0.0200 "), std::string::npos) << md;
  std::istringstream lines(md);
  for (std::string line; std::getline(lines, line);) {
    size_t width = 0;
    for (unsigned char c : line) width += (c & 0xC0) != 0x80;
    EXPECT_LE(width, 120u) << line;
  }
}

TEST(SummaryTables, GridPointsGetAParametersColumn) {
  ResultsTable t;
  t.grid_keys = {"sensors.lidar.sigma_range_m"};
  t.metric_keys = {"ate_rmse_m"};
  for (const char* v : {"0.01", "0.05"})
    for (std::uint64_t s = 0; s < 10; ++s)
      t.rows.push_back({.run_id = std::string(v) + std::to_string(s), .scenario = "loop", .seed = s, .algorithm = "a",
                        .status = "ok", .grid = {{"sensors.lidar.sigma_range_m", v}},
                        .metrics = {{"ate_rmse_m", 0.1 + 0.01 * s}}});
  const std::string md = ScenarioSummary(t, "loop", IntervalMethod::kAuto);
  EXPECT_NE(md.find("| a         | sigma_range_m=0.01 |"), std::string::npos) << md;  // the key's last part
  EXPECT_NE(md.find("(Student-t)"), std::string::npos) << md;  // 10 seeds: the t-interval
}

}  // namespace
}  // namespace slambox
