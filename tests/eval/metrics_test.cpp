// The typed metrics record and its descriptor table: one key per field, the serializer and
// the reader agree, the schema (eval/README.md) lists every key, bad entries name the key.
#include "eval/metrics.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>

#include "core/error.hpp"
#include "eval/evaluate.hpp"

namespace slambox {
namespace {

using nlohmann::json;

Evaluation Evaluated() {
  GroundTruth gt;
  Estimate est;
  for (int i = 0; i <= 40; ++i) {
    const double t = 0.1 * i;
    const SE2 truth(0.5 * i, 0.1 * i * i / 40.0, 0.02 * i);
    gt.trajectory.push_back({t, truth});
    Eigen::Matrix3d cov = Eigen::Matrix3d::Identity() * 0.01;
    est.trajectory.push_back({t, SE2(truth.x + 0.01 * std::sin(i), truth.y - 0.02, truth.theta + 0.001 * i), cov, true});
    est.step_time_s.push_back(1e-4);
  }
  return EvaluateEstimate(gt, est);
}

TEST(MetricTable, KeysAreUniqueUndottedAndLabelled) {
  std::set<std::string> keys;
  for (const auto& d : MetricTable()) {
    EXPECT_TRUE(keys.insert(d.key).second) << "duplicate key " << d.key;
    EXPECT_EQ(d.key.find('.'), std::string::npos) << d.key << ": results.csv tells grid columns by their dot";
    EXPECT_FALSE(d.label.empty()) << d.key;
    EXPECT_EQ(FindMetric(d.key), &d);
  }
  EXPECT_EQ(FindMetric("sensors.lidar.sigma_range_m"), nullptr);
  const auto summary = SummaryMetrics();
  ASSERT_EQ(summary.size(), 6u);
  for (size_t i = 0; i < summary.size(); ++i) EXPECT_EQ(summary[i]->summary_column, static_cast<int>(i));
  EXPECT_EQ(summary[0]->key, "ate_rmse_m");
  EXPECT_EQ(summary[2]->label, "RPE trans [m]");
  EXPECT_TRUE(FindMetric("rpe_trans_max_m")->checked);
  EXPECT_FALSE(FindMetric("rpe_pairs")->checked);
  EXPECT_TRUE(FindMetric("anees")->checked);  // for drift, either way
  EXPECT_EQ(FindMetric("anees")->better, Better::kNeither);
  EXPECT_FALSE(FindMetric("ate_min_m")->checked);
  EXPECT_TRUE(FindMetric("step_time_p95_s")->timing);
  EXPECT_FALSE(FindMetric("ate_rmse_m")->timing);
  EXPECT_TRUE(FindMetric("heading_rmse_deg")->evo);
  EXPECT_FALSE(FindMetric("kitti_trans_percent")->evo);
}

TEST(MetricTable, EveryKeyIsInTheSchema) {
  std::ifstream in(std::string(SLAMBOX_SOURCE_DIR) + "/eval/README.md");
  std::stringstream s;
  s << in.rdbuf();
  const std::string readme = s.str();
  ASSERT_FALSE(readme.empty());
  for (const auto& d : MetricTable())
    EXPECT_NE(readme.find("`" + d.key + "`"), std::string::npos) << d.key << " is not documented in eval/README.md";
}

TEST(Metrics, SerializerAndReaderRoundTrip) {
  const Evaluation ev = Evaluated();
  const json j = ToJson(ev.metrics);
  EXPECT_EQ(j.at("status"), "ok");
  EXPECT_TRUE(j.at("ate_rmse_m").is_number());
  EXPECT_TRUE(j.at("landmark_rmse_m").is_null());      // no landmark map: not applicable
  EXPECT_TRUE(j.at("loop_closures").is_null());        // builds no graph
  EXPECT_TRUE(j.at("matched_poses").is_number_integer());
  EXPECT_FALSE(j.contains("reason"));                  // empty strings are left out
  for (const auto& d : MetricTable()) {
    if (d.key != "reason" && d.key != "note" && d.key != "alignment_reason") {
      EXPECT_TRUE(j.contains(d.key)) << d.key;
    }
  }
  const Metrics back = MetricsFromJson(j, "x.json");
  EXPECT_EQ(ToJson(back).dump(), j.dump());
  EXPECT_EQ(back.ate.rmse, ev.metrics.ate.rmse);
  EXPECT_DOUBLE_EQ(MetricNumber(*FindMetric("ate_rmse_m"), back), j.at("ate_rmse_m").get<double>());
  EXPECT_TRUE(std::isnan(MetricNumber(*FindMetric("landmark_rmse_m"), back)));
  EXPECT_TRUE(std::isnan(MetricNumber(*FindMetric("status"), back)));
}

TEST(Metrics, AModuleThatThrewHasOnlyStatusAndReason) {
  const Metrics failed = UnscoredMetrics(RunStatus::kFailed, "boom");
  EXPECT_EQ(ToJson(failed), (json{{"status", "failed"}, {"reason", "boom"}}));
  const Metrics back = MetricsFromJson(ToJson(failed), "x.json");
  EXPECT_FALSE(back.scored);
  EXPECT_EQ(back.reason, "boom");
  EXPECT_TRUE(std::isnan(MetricNumber(*FindMetric("relation_count"), back)));  // not 0
  EXPECT_EQ(ToJson(MetricsFromJson(json{{"status", "failed"}}, "f.json")), (json{{"status", "failed"}}));
}

TEST(Metrics, AWrongTypeNamesTheFileAndTheKey) {
  json j = ToJson(Evaluated().metrics);
  j["ate_rmse_m"] = "small";
  try {
    MetricsFromJson(j, "run/metrics.json");
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("run/metrics.json"), std::string::npos) << msg;
    EXPECT_NE(msg.find("ate_rmse_m"), std::string::npos) << msg;
  }
  EXPECT_THROW(MetricsFromJson(json{{"status", "great"}}, "x.json"), InputError);
  EXPECT_THROW(MetricsFromJson(json::array(), "x.json"), InputError);
  // A key this version does not know is ignored (a newer writer).
  EXPECT_NO_THROW(MetricsFromJson(json{{"status", "ok"}, {"future_metric_m", 1.0}}, "x.json"));
}

}  // namespace
}  // namespace slambox
