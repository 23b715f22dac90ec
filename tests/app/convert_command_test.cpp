// `slambox convert carmen` end to end: a converted log replays through `slambox run`
// (status ok, pose errors null: no ground truth), bad logs exit non-zero naming the line,
// and icp-poseslam maps the public Intel log when it is present.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/support/public_data.hpp"
#include "tests/support/slambox_cli.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kBinary = SLAMBOX_BINARY;

using Result = slambox::testing::CliResult;

Result Slambox(const std::string& args) { return slambox::testing::RunSlambox(kBinary, args); }

fs::path TempDir(const std::string& name) { return slambox::testing::FreshTempDir("convert_" + name); }

// A robot driving straight down a 4 m wide corridor with a wall ahead, 181-beam scans.
std::string CorridorLog() {
  std::ostringstream s;
  s.precision(9);
  for (int k = 0; k < 30; ++k) {
    const double x = 0.05 * k, ts = 500.0 + 0.1 * k;
    s << "ODOM " << x << " 0 0 0.5 0 0 " << ts << " host 0\n";
    s << "FLASER 181";
    for (int i = 0; i < 181; ++i) {
      const double a = -M_PI / 2 + i * M_PI / 180;
      const double side = std::abs(std::sin(a)) > 1e-9 ? 2.0 / std::abs(std::sin(a)) : 1e9;
      const double ahead = std::cos(a) > 1e-9 ? (10.0 - x) / std::cos(a) : 1e9;
      s << " " << std::min({side, ahead, 81.0});
    }
    s << " " << x << " 0 0 " << x << " 0 0 " << ts + 0.01 << " host 0\n";
  }
  return s.str();
}

TEST(Convert, CarmenLogReplaysThroughRunWithoutGroundTruth) {
  const fs::path dir = TempDir("corridor");
  std::ofstream(dir / "corridor.clf") << CorridorLog();
  const Result c = Slambox("convert carmen " + (dir / "corridor.clf").string() + " -o " + (dir / "c.stream").string());
  ASSERT_EQ(c.code, 0) << c.output;
  EXPECT_NE(c.output.find("30 scans (181 beams over 180.0 deg"), std::string::npos) << c.output;
  const Result r = Slambox("run " + (dir / "c.stream").string() + " --algo odometry,icp-odometry --no-figures -q -o " +
                           (dir / "run").string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(dir / "run" / "metrics.json");
  const json m = json::parse(in);
  EXPECT_EQ(m.at("converted_log"), true);
  EXPECT_TRUE(m.at("distance_m").is_null());  // a log's true path is unknown (it was 0.0)
  for (const char* name : {"odometry", "icp-odometry"}) {
    const json& a = m.at("algorithms").at(name);
    EXPECT_EQ(a.at("status"), "ok") << a.dump();
    EXPECT_TRUE(a.at("ate_rmse_m").is_null());
    EXPECT_TRUE(a.at("distance_m").is_null());
    EXPECT_EQ(a.at("alignment_reason"), "the stream has no ground truth");
    EXPECT_TRUE(a.contains("note"));
    EXPECT_GT(a.at("realtime_factor").get<double>(), 0.0);
  }
  EXPECT_TRUE(fs::exists(dir / "run" / "icp-odometry.tum"));
  // A converted log has no map: `all` skips the localization modules, naming one fails clearly.
  const Result all = Slambox("run " + (dir / "c.stream").string() + " --algo all --no-figures -q -o " + (dir / "all").string());
  ASSERT_EQ(all.code, 0) << all.output;
  std::ifstream all_in(dir / "all" / "metrics.json");
  const json algorithms = json::parse(all_in).at("algorithms");
  EXPECT_TRUE(algorithms.contains("icp-poseslam"));
  EXPECT_FALSE(algorithms.contains("mcl"));
  EXPECT_FALSE(algorithms.contains("icp-localization"));
  const Result mcl = Slambox("run " + (dir / "c.stream").string() + " --algo mcl --no-figures -q -o " + (dir / "mcl").string());
  EXPECT_NE(mcl.code, 0);
  EXPECT_NE(mcl.output.find("known map"), std::string::npos) << mcl.output;
  fs::remove_all(dir);
}

json ReadJson(const fs::path& path) {
  std::ifstream in(path);
  return json::parse(in);
}

// Relations between the corridor log's scans (laser at (x, 0, 0), scan k at 500.01 + 0.1 k
// on the log's clock). The odometry is exact, so an exact relation scores 0; one is off by
// (0.1 m, 0.1 rad) and one names a time with no pose within 5 ms. Unsorted on purpose.
std::string CorridorRelations() {
  std::ostringstream s;
  s.precision(12);
  s << 500.51 << " " << 501.01 << " 0.25 0 0 0 0 0\n";        // scans 5 -> 10: exact
  s << 500.01 << " " << 500.51 << " 0.35 0 0 0 0 0.1\n";      // scans 0 -> 5: off by 0.1 m, 0.1 rad
  s << 500.01 << " " << 500.05 << " 0.0 0 0 0 0 0\n";         // 500.05: 40 ms from any event
  return s.str();
}

TEST(Convert, RelationsScoreAConvertedLogInRunEvalAndSweep) {
  const fs::path dir = TempDir("relations");
  std::ofstream(dir / "corridor.clf") << CorridorLog();
  std::ofstream(dir / "corridor.relations") << CorridorRelations();
  const std::string stream = (dir / "c.stream").string(), rel = (dir / "corridor.relations").string();
  ASSERT_EQ(Slambox("convert carmen " + (dir / "corridor.clf").string() + " -o " + stream).code, 0);
  const Result r = Slambox("run " + stream + " --algo odometry --relations " + rel + " --no-figures -q -o " +
                           (dir / "run").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const json doc = ReadJson(dir / "run" / "metrics.json");
  EXPECT_EQ(doc.at("time_origin_s"), 500.0);  // the log's first timestamp
  EXPECT_EQ(doc.at("relations_file"), rel);
  const json a = doc.at("algorithms").at("odometry");
  EXPECT_EQ(a.at("relation_count"), 2);
  EXPECT_EQ(a.at("relation_unmatched"), 1);
  EXPECT_NEAR(a.at("relation_trans_mean_m").get<double>(), 0.05, 1e-9);
  EXPECT_NEAR(a.at("relation_trans_std_m").get<double>(), 0.05, 1e-9);
  EXPECT_NEAR(a.at("relation_rot_mean_deg").get<double>(), 0.05 * 180 / M_PI, 1e-7);
  EXPECT_NEAR(a.at("relation_trans_sq_mean_m2").get<double>(), 0.005, 1e-9);

  // eval on the written estimate: the same numbers with the stream's origin or the origin given.
  const std::string est = (dir / "run" / "odometry.tum").string();
  for (const std::string origin : {" --stream " + stream, std::string(" --time-origin-s 500")}) {
    const Result e = Slambox("eval --est " + est + " --relations " + rel + origin + " --json");
    ASSERT_EQ(e.code, 0) << e.output;
    const json m = json::parse(e.output);
    EXPECT_EQ(m.at("relation_count"), 2);
    EXPECT_EQ(m.at("relation_unmatched"), 1);
    EXPECT_EQ(m.at("relation_trans_mean_m"), a.at("relation_trans_mean_m"));
  }
  // Without the origin nothing matches: one clear error naming the fix.
  const Result none = Slambox("eval --est " + est + " --relations " + rel);
  EXPECT_NE(none.code, 0);
  EXPECT_NE(none.output.find("--stream"), std::string::npos) << none.output;
  const Result nothing = Slambox("eval --est " + est);
  EXPECT_NE(nothing.code, 0);
  // Relations of another log (times outside the stream) fail before anything is written.
  std::ofstream(dir / "other.relations") << "976052905.1 976052906.1 1 0 0 0 0 0\n";
  const Result other = Slambox("run " + stream + " --relations " + (dir / "other.relations").string() +
                               " --no-figures -q -o " + (dir / "other").string());
  EXPECT_NE(other.code, 0);
  EXPECT_NE(other.output.find("other.relations"), std::string::npos) << other.output;
  EXPECT_FALSE(fs::exists(dir / "other"));
  std::ofstream(dir / "bad.relations") << "500.01 500.51 0.35 0 0\n";
  const Result bad = Slambox("run " + stream + " --relations " + (dir / "bad.relations").string() +
                             " --no-figures -q -o " + (dir / "bad").string());
  EXPECT_NE(bad.code, 0);
  EXPECT_NE(bad.output.find("bad.relations:1"), std::string::npos) << bad.output;

  // A sweep over the stream with its relations: one run (a stream has no seeds), relation columns.
  std::ofstream(dir / "sweep.yaml") << "scenarios: [" << stream << "]\nalgorithms: [odometry]\nseeds: 3\n"
                                    << "relations: {" << stream << ": " << rel << "}\n";
  const Result sw = Slambox("sweep " + (dir / "sweep.yaml").string() + " -j 1 --no-figures -o " + (dir / "sweep").string());
  ASSERT_EQ(sw.code, 0) << sw.output;
  std::ifstream csv(dir / "sweep" / "results.csv");
  std::string header, row, extra;
  std::getline(csv, header);
  std::getline(csv, row);
  EXPECT_FALSE(std::getline(csv, extra)) << "one run expected, got another row: " << extra;
  EXPECT_NE(header.find("relation_unmatched"), std::string::npos) << header;
  EXPECT_NE(row.find(",ok,"), std::string::npos) << row;
  // Scenario keys cannot apply to a stream: rejected when the sweep file is read.
  std::ofstream(dir / "bad_sweep.yaml") << "scenarios: [" << stream << "]\nalgorithms: [odometry]\nseeds: 1\n"
                                        << "grid: {robot.laps: [1, 2]}\n";
  const Result bs = Slambox("sweep " + (dir / "bad_sweep.yaml").string() + " -o " + (dir / "bad_sweep").string());
  EXPECT_NE(bs.code, 0);
  EXPECT_NE(bs.output.find("robot.laps"), std::string::npos) << bs.output;
  fs::remove_all(dir);
}

TEST(Convert, BadLogExitsNonZeroNamingTheLine) {
  const fs::path dir = TempDir("bad");
  std::ofstream(dir / "bad.clf") << "ODOM 0 0 0 0 0 0 1.0 host 0\nFLASER 3 1.0 2.0 0 0 0 0 0 0 1.5 host 0\n";
  const Result r = Slambox("convert carmen " + (dir / "bad.clf").string() + " -o " + (dir / "x.stream").string());
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("bad.clf:2"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "x.stream"));
  const Result missing = Slambox("convert carmen " + (dir / "none.clf").string() + " -o " + (dir / "x.stream").string());
  EXPECT_NE(missing.code, 0);
  fs::remove_all(dir);
}

// The relation metric on a public log against ../shared/tools/relations_eval.py, an
// independent implementation: dead reckoning on intel and fr079 (deterministic, so the
// numbers are pinned; the script printed them for the same estimates).
TEST(Convert, RelationMetricOnPublicLogsMatchesTheIndependentScript) {
  struct Expected {
    const char* log;
    int relations;
    double trans_mean_m, trans_std_m, rot_mean_deg, rot_std_deg;
  };
  for (const Expected& x : {Expected{"intel", 2984, 7.3744523523900165, 14.346969484629422, 39.25081599522632, 53.73641426100169},
                            Expected{"fr079", 1685, 6.507205851715992, 13.657073652660364, 30.29217719872455, 45.520471399677106}}) {
    const std::string log = slambox::testing::PublicDataFile(SLAMBOX_SOURCE_DIR, std::string("rawlogs/") + x.log + ".clf.bz2");
    const std::string rel = slambox::testing::PublicDataFile(SLAMBOX_SOURCE_DIR, std::string("relations/") + x.log + ".relations");
    if (log.empty() || rel.empty()) GTEST_SKIP() << "public data absent (../shared/data or $SLAMBOX_DATA)";
    const fs::path dir = TempDir(std::string("rel_") + x.log);
    ASSERT_EQ(Slambox("convert carmen " + log + " -o " + (dir / "s.stream").string()).code, 0);
    const Result r = Slambox("run " + (dir / "s.stream").string() + " --algo odometry --relations " + rel +
                             " --no-figures -q -o " + (dir / "run").string());
    ASSERT_EQ(r.code, 0) << r.output;
    const json a = ReadJson(dir / "run" / "metrics.json").at("algorithms").at("odometry");
    EXPECT_EQ(a.at("relation_count"), x.relations) << x.log;
    EXPECT_EQ(a.at("relation_unmatched"), 0) << x.log;
    EXPECT_NEAR(a.at("relation_trans_mean_m").get<double>(), x.trans_mean_m, 1e-9) << x.log;
    EXPECT_NEAR(a.at("relation_trans_std_m").get<double>(), x.trans_std_m, 1e-9) << x.log;
    EXPECT_NEAR(a.at("relation_rot_mean_deg").get<double>(), x.rot_mean_deg, 1e-9) << x.log;
    EXPECT_NEAR(a.at("relation_rot_std_deg").get<double>(), x.rot_std_deg, 1e-9) << x.log;
    EXPECT_TRUE(a.at("loop_closure_precision").is_null());
    fs::remove_all(dir);
  }
}

TEST(Convert, IcpPoseSlamMapsTheIntelLogWhenPresent) {
  const std::string intel = slambox::testing::PublicDataFile(SLAMBOX_SOURCE_DIR, "rawlogs/intel.clf.bz2");
  if (intel.empty()) GTEST_SKIP() << "public data absent (../shared/data or $SLAMBOX_DATA)";
  const fs::path dir = TempDir("intel");
  ASSERT_EQ(Slambox("convert carmen " + intel + " -o " + (dir / "intel.stream").string()).code, 0);
  const Result r = Slambox("run " + (dir / "intel.stream").string() + " --algo icp-poseslam --no-figures -q -o " +
                           (dir / "run").string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(dir / "run" / "metrics.json");
  const json a = json::parse(in).at("algorithms").at("icp-poseslam");
  EXPECT_EQ(a.at("status"), "ok");
  // 45 minutes around the lab's corridors: many verified closures (318 at the time of writing).
  EXPECT_GT(a.at("loop_closures").get<int>(), 150) << a.dump();
  // No ground truth: precision and the grid are not scored (they were 0.0 and "vs. nothing").
  EXPECT_TRUE(a.at("loop_closure_precision").is_null());
  EXPECT_TRUE(a.at("grid_cell_error").is_null());
  fs::remove_all(dir);
}

}  // namespace

namespace {

TEST(Convert, EkfSlamMapsVictoriaParkWhenPresent) {
  const std::string vp =
      slambox::testing::PublicDataFile(SLAMBOX_SOURCE_DIR, "landmark/victoria_park/islsjf/VicPark_clean_data.txt");
  if (vp.empty()) GTEST_SKIP() << "public data absent (../shared/data or $SLAMBOX_DATA)";
  const fs::path dir = TempDir("vp");
  ASSERT_EQ(Slambox("convert victoria-park " + vp + " -o " + (dir / "vp.stream").string()).code, 0);
  const Result r = Slambox("run " + (dir / "vp.stream").string() + " --algo ekf-slam --no-figures -q -o " + (dir / "run").string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(dir / "run" / "metrics.json");
  EXPECT_EQ(json::parse(in).at("algorithms").at("ekf-slam").at("status"), "ok");
  std::ifstream est(dir / "run" / "estimates" / "ekf-slam.json");
  const json e = json::parse(est);
  EXPECT_GT(e.at("landmarks").size(), 100u);  // trees mapped with known ids
  fs::remove_all(dir);
}

}  // namespace

namespace {

// `convert graph` end to end: a noise-free three-pose iSAM graph with its ground truth
// replays through `run` with pose metrics (dead reckoning is exact on it), the report line
// counts what was left out, and bad graphs exit non-zero naming the file and line.
TEST(Convert, GraphWithGroundTruthReplaysThroughRun) {
  const fs::path dir = TempDir("graph");
  std::ofstream(dir / "g.txt") << "ODOMETRY 0 1 1 0 0 10 0 0 10 0 20\n"
                                  "ODOMETRY 2 1 0 1 -1.5707963267948966 10 0 0 10 0 20\n"  // 1 -> 2, stated backwards
                                  "ODOMETRY 0 2 2 0 1.5707963267948966 10 0 0 10 0 20\n"   // a loop closure
                                  "LANDMARK 0 7 3 4 10 0 10\nLANDMARK 1 8 0 2 10 0 10\nLANDMARK 2 7 4 -1 10 0 10\n";
  std::ofstream(dir / "poses.txt") << "0 0 0 0\n1 1 0 0\n2 2 0 1.5707963267948966\n";
  std::ofstream(dir / "trees.txt") << "7 3 4\n8 1 2\n";
  const std::string stream = (dir / "g.stream").string();
  const Result c = Slambox("convert graph " + (dir / "g.txt").string() + " -o " + stream + " --groundtruth " +
                           (dir / "poses.txt").string() + " --groundtruth " + (dir / "trees.txt").string());
  ASSERT_EQ(c.code, 0) << c.output;
  for (const char* part : {"2 odometry steps (1 stated backwards, inverted)", "3 landmark sightings of 2 landmarks",
                           "noise read as sqrt-information", "1 pose edges off the odometry chain left out",
                           "with ground truth"})
    EXPECT_NE(c.output.find(part), std::string::npos) << part << "\n" << c.output;
  const Result r = Slambox("run " + stream + " --algo odometry,ekf-slam --no-figures -q -o " + (dir / "run").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const json metrics = ReadJson(dir / "run" / "metrics.json");
  EXPECT_EQ(metrics.at("converted_log"), true);
  EXPECT_TRUE(metrics.at("distance_m").is_number());  // its ground truth's path  // ground truth or not, a log has no seed to show
  const json& algorithms = metrics.at("algorithms");
  for (const char* name : {"odometry", "ekf-slam"}) {
    const json& a = algorithms.at(name);
    EXPECT_EQ(a.at("status"), "ok") << a.dump();
    ASSERT_TRUE(a.at("ate_rmse_m").is_number()) << a.dump();
    EXPECT_LT(a.at("ate_rmse_m").get<double>(), 1e-6) << name;
  }
  EXPECT_TRUE(algorithms.at("ekf-slam").at("landmark_rmse_m").is_number());

  std::ofstream(dir / "nan.txt") << "ODOMETRY 0 1 1 0 0 10 0 0 10 0 20\nLANDMARK 1 0 nan 0 10 0 10\n";
  const Result nan = Slambox("convert graph " + (dir / "nan.txt").string() + " -o " + (dir / "x.stream").string());
  EXPECT_NE(nan.code, 0);
  EXPECT_NE(nan.output.find("nan.txt:2"), std::string::npos) << nan.output;
  std::ofstream(dir / "pose_only.txt") << "ODOMETRY 0 1 1 0 0 10 0 0 10 0 20\n";
  const Result pose_only = Slambox("convert graph " + (dir / "pose_only.txt").string() + " -o " + (dir / "x.stream").string());
  EXPECT_NE(pose_only.code, 0);
  EXPECT_NE(pose_only.output.find("no landmark edge"), std::string::npos) << pose_only.output;
  std::ofstream(dir / "short.txt") << "0 0 0 0\n1 1 0 0\n";
  const Result short_truth = Slambox("convert graph " + (dir / "g.txt").string() + " -o " + (dir / "x.stream").string() +
                                     " --groundtruth " + (dir / "short.txt").string());
  EXPECT_NE(short_truth.code, 0);
  EXPECT_NE(short_truth.output.find("short.txt: no true pose for pose id 2"), std::string::npos) << short_truth.output;
  const Result period = Slambox("convert graph " + (dir / "g.txt").string() + " -o " + (dir / "x.stream").string() +
                                " --pose-period-s 0");
  EXPECT_NE(period.code, 0);
  const Result alpha = Slambox("convert graph " + (dir / "g.txt").string() + " -o " + (dir / "x.stream").string() +
                               " --odometry-alpha 0.1,-1,0.1,0.1");
  EXPECT_NE(alpha.code, 0);
  EXPECT_NE(alpha.output.find("--odometry-alpha"), std::string::npos) << alpha.output;
  EXPECT_FALSE(fs::exists(dir / "x.stream"));
  fs::remove_all(dir);
}

}  // namespace
