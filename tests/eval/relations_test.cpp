// Kümmerle relation files: parsing (unsorted, comments, errors with line numbers), the
// error e = d_ref^-1 (x_i^-1 x_j) against hand-computed values (incl. the angle wrap at
// +-pi), time mapping by the origin, the matching tolerance, and unmatched relations
// counted; then the relation_* keys of EvaluateEstimate on a stream without ground truth.
#include "eval/relations.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "eval/evaluate.hpp"
#include "eval/relation_metric.hpp"

namespace slambox {
namespace {

constexpr double kDeg = M_PI / 180.0;

// Three poses at t = 0, 1, 2 s (stream clock).
std::vector<StampedPose> Trajectory() {
  return {{0.0, SE2(0.0, 0.0, 0.0)}, {1.0, SE2(1.0, 0.0, 90 * kDeg)}, {2.0, SE2(1.0, 1.0, 179 * kDeg)}};
}

TEST(Relations, ParsesUnsortedFileSkippingCommentsAndBlankLines) {
  const auto r = ParseRelations("# t_i t_j dx dy dz roll pitch dtheta\n"
                                "101 102 0.5 0.25 0 0 0 0.1\n\n"
                                "100 101 1 0 0 0 0 1.5707963267948966\n",
                                "x.relations");
  ASSERT_EQ(r.size(), 2u);
  EXPECT_DOUBLE_EQ(r[0].t_i_s, 101.0);
  EXPECT_DOUBLE_EQ(r[0].T_i_j.y, 0.25);
  EXPECT_DOUBLE_EQ(r[0].T_i_j.theta, 0.1);
  EXPECT_EQ(r[0].line, 2);
  EXPECT_EQ(r[1].line, 4);
}

TEST(Relations, BadLinesNameTheFileAndLine) {
  try {
    ParseRelations("100 101 1 0 0 0 0 0\n100 101 1 0 0 0\n", "bad.relations");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 2);
    EXPECT_NE(std::string(e.what()).find("bad.relations:2"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("expected 8 numbers"), std::string::npos);
  }
  EXPECT_THROW(ParseRelations("100 101 1 nan 0 0 0 0\n", "n.relations"), InputError);
  EXPECT_THROW(ParseRelations("100 101 1 0x 0 0 0 0\n", "n.relations"), InputError);
  EXPECT_THROW(ParseRelations("# only a comment\n", "empty.relations"), InputError);
  EXPECT_THROW(ReadRelations("/nonexistent/x.relations"), InputError);
}

TEST(Relations, AbsurdValuesAreRefusedAtTheirLine) {
  // Found by tests/fuzz/fuzz_relations: a finite -0.91e308 displacement overflowed the
  // relation error to infinity. Every field is now bounded (core/limits.hpp).
  const auto refused = [](const std::string& text, const std::string& field) {
    try {
      ParseRelations(text, "absurd.relations");
      ADD_FAILURE() << text << ": accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.line(), 2) << e.what();
      EXPECT_NE(std::string(e.what()).find("field " + field), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("out of range"), std::string::npos) << e.what();
    }
  };
  const std::string good = "0.1 0.5 0.2 -0.9 0 0 0 0.3\n";
  refused(good + "0.1 0.5 0.2 -0.91e308 0 0 0 0.3\n", "4");
  refused(good + "2e10 0.5 0.2 0 0 0 0 0.3\n", "1");
  refused(good + "0.1 0.5 0.2 0 0 0 0 1e5\n", "8");
  refused(good + "0.1 0.5 0.2 0 1e6 0 0 0\n", "5");
  // The largest accepted values score finitely.
  const auto relations = ParseRelations(good + "0.1 0.5 1e5 -1e5 0 0 0 1e4\n", "edge.relations");
  const std::vector<StampedPose> trajectory = {{0.1, SE2{}}, {0.5, SE2{1.0, 0.0, 0.0}}};
  for (double e : ComputeRelationErrors(relations, trajectory).translation_m) EXPECT_TRUE(std::isfinite(e));
}

TEST(Relations, HandComputedErrorsInFileOrderWithTheTimeOrigin) {
  // Log clock = stream clock + 1000. Relation 0 is exact: x_0^-1 x_1 = (1, 0, 90°).
  // Relation 1 (listed first: unsorted): x_1^-1 x_2 = (1, 0, 89°) (x_2 - x_1 = (0, 1) seen
  // from heading 90° is (1, 0)); the reference says (0.9, 0.1, 80°):
  // e = ref^-1 d = R(-80°)(0.1, -0.1), 9° -> |t| = sqrt(0.02), 9°.
  const std::vector<Relation> rel = {{1001.0, 1002.0, SE2(0.9, 0.1, 80 * kDeg)},
                                     {1000.0, 1001.0, SE2(1.0, 0.0, 90 * kDeg)}};
  const RelationErrors e = ComputeRelationErrors(rel, Trajectory(), {.time_origin_s = 1000.0});
  ASSERT_EQ(e.translation_m.size(), 2u);
  EXPECT_EQ(e.unmatched, 0);
  EXPECT_NEAR(e.translation_m[0], std::sqrt(0.02), 1e-12);
  EXPECT_NEAR(e.rotation_deg[0], 9.0, 1e-9);
  EXPECT_NEAR(e.translation_m[1], 0.0, 1e-12);
  EXPECT_NEAR(e.rotation_deg[1], 0.0, 1e-9);
  // Mean ± std (ddof 0) and squares as in Hess et al. 2016 Table II.
  const RelationMetric m = ComputeRelationMetric(e.translation_m, e.rotation_deg);
  EXPECT_EQ(m.relations, 2);
  EXPECT_NEAR(m.trans_mean_m, std::sqrt(0.02) / 2, 1e-12);
  EXPECT_NEAR(m.trans_std_m, std::sqrt(0.02) / 2, 1e-12);
  EXPECT_NEAR(m.trans_sq_mean_m2, 0.01, 1e-12);
  EXPECT_NEAR(m.rot_mean_deg, 4.5, 1e-9);
  EXPECT_NEAR(m.rot_sq_mean_deg2, 40.5, 1e-7);
}

TEST(Relations, RotationErrorWrapsAtPlusMinusPi) {
  // x_0 at heading 179°, x_1 at -179°: the estimated relative heading is +2°; a reference
  // of -178° (= +182°) differs by 180°, one of +-1° by 1° or 3°, never by 358°.
  const std::vector<StampedPose> traj = {{0.0, SE2(0, 0, 179 * kDeg)}, {1.0, SE2(0, 0, -179 * kDeg)}};
  const auto err = [&](double ref_deg) {
    return ComputeRelationErrors({{0.0, 1.0, SE2(0, 0, ref_deg * kDeg)}}, traj).rotation_deg.at(0);
  };
  EXPECT_NEAR(err(2.0), 0.0, 1e-9);
  EXPECT_NEAR(err(1.0), 1.0, 1e-9);
  EXPECT_NEAR(err(-1.0), 3.0, 1e-9);
  EXPECT_NEAR(err(-178.0), 180.0, 1e-9);
  EXPECT_NEAR(err(-179.0), 179.0, 1e-9);
}

TEST(Relations, TimesFartherThanTheToleranceAreCountedUnmatched) {
  const std::vector<StampedPose> traj = Trajectory();
  const std::vector<Relation> rel = {
      {0.004, 1.0, SE2(1, 0, 90 * kDeg)},   // 4 ms off: matched (tolerance 5 ms)
      {0.0, 1.006, SE2(1, 0, 90 * kDeg)},   // 6 ms off: unmatched
      {-0.5, 1.0, SE2(1, 0, 90 * kDeg)},    // before the first pose
      {1.0, 7.0, SE2(0, 0, 0)}};            // after the last
  const RelationErrors e = ComputeRelationErrors(rel, traj);
  EXPECT_EQ(e.translation_m.size(), 1u);
  EXPECT_EQ(e.unmatched, 3);
  EXPECT_EQ(ComputeRelationErrors(rel, traj, {.max_time_diff_s = 0.01}).unmatched, 2);
  // Halfway between two poses: the earlier one (ties go to the earlier pose).
  const RelationErrors tie = ComputeRelationErrors({{0.5, 1.0, SE2(1, 0, 90 * kDeg)}}, traj, {.max_time_diff_s = 0.5});
  ASSERT_EQ(tie.translation_m.size(), 1u);
  EXPECT_NEAR(tie.translation_m[0], 0.0, 1e-12);
  EXPECT_EQ(RelationsWithin(rel, 2.0, {}), 2);
  EXPECT_EQ(RelationsWithin(rel, 2.0, {.time_origin_s = 100.0}), 0);
}

TEST(Relations, EvaluateWritesRelationKeysWithoutGroundTruth) {
  GroundTruth none;
  Estimate est;
  for (const auto& p : Trajectory()) est.trajectory.push_back({p.t_s, p.pose, Eigen::Matrix3d::Zero(), false});
  EvalOptions o;
  o.relations = {{1001.0, 1002.0, SE2(0.9, 0.1, 80 * kDeg)}, {1000.0, 1001.0, SE2(1.0, 0.0, 90 * kDeg)},
                 {1000.0, 1010.0, SE2()}};
  o.relation_matching.time_origin_s = 1000.0;
  const auto m = ToJson(EvaluateEstimate(none, est, o).metrics);
  EXPECT_EQ(m["relation_count"], 2);
  EXPECT_EQ(m["relation_unmatched"], 1);
  EXPECT_NEAR(m["relation_trans_mean_m"].get<double>(), std::sqrt(0.02) / 2, 1e-12);
  EXPECT_NEAR(m["relation_rot_mean_deg"].get<double>(), 4.5, 1e-9);
  EXPECT_NEAR(m["relation_trans_sq_mean_m2"].get<double>(), 0.01, 1e-12);
  EXPECT_NEAR(m["relation_rot_sq_mean_deg2"].get<double>(), 40.5, 1e-7);
  EXPECT_TRUE(m["ate_rmse_m"].is_null());
  // Without a relations file the RPE pairs are the relations and nothing is "unmatched".
  const auto rpe = ToJson(EvaluateEstimate(none, est).metrics);
  EXPECT_EQ(rpe["relation_count"], 0);
  EXPECT_TRUE(rpe["relation_unmatched"].is_null());
  EXPECT_TRUE(rpe["relation_trans_mean_m"].is_null());
}

}  // namespace
}  // namespace slambox
