#include "eval/evaluate.hpp"

#include <cmath>
#include <limits>

#include "eval/alignment.hpp"
#include "eval/association.hpp"
#include "eval/ate.hpp"
#include "core/chi_square.hpp"
#include "eval/consistency.hpp"
#include "eval/cost.hpp"
#include "eval/relation_metric.hpp"
#include "eval/statistics.hpp"

namespace slambox {

namespace {
using nlohmann::json;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

json NumberArray(const std::vector<double>& v) {
  json a = json::array();
  for (double x : v) a.push_back(NumberOrNull(x));
  return a;
}

bool Finite(const SE2& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta); }

// Pose error metrics: ate_*, ate_aligned_*, heading_*, rpe_*, kitti_*, relation_*.
// The estimate moved by the requested alignment (none: unchanged).
std::vector<SE2> AlignedEstimate(const Association& a, AlignMode mode, const AlignmentResult& umeyama) {
  if (a.estimate.empty()) return {};
  if (mode == AlignMode::kSE2 && umeyama.valid) return TransformPoses(umeyama.T_gt_est, a.estimate);
  if (mode == AlignMode::kOrigin)
    return TransformPoses(OriginAlignment(a.groundtruth.front(), a.estimate.front()), a.estimate);
  return a.estimate;
}

// relation_* keys (eval/README.md); `unmatched` is null when the relations are RPE pairs.
void AddRelationMetric(const RelationMetric& rel, const json& unmatched, json& m) {
  m["relation_count"] = rel.relations;
  m["relation_unmatched"] = unmatched;
  m["relation_trans_mean_m"] = NumberOrNull(rel.trans_mean_m);
  m["relation_trans_std_m"] = NumberOrNull(rel.trans_std_m);
  m["relation_trans_sq_mean_m2"] = NumberOrNull(rel.trans_sq_mean_m2);
  m["relation_trans_sq_std_m2"] = NumberOrNull(rel.trans_sq_std_m2);
  m["relation_rot_mean_deg"] = NumberOrNull(rel.rot_mean_deg);
  m["relation_rot_std_deg"] = NumberOrNull(rel.rot_std_deg);
  m["relation_rot_sq_mean_deg2"] = NumberOrNull(rel.rot_sq_mean_deg2);
  m["relation_rot_sq_std_deg2"] = NumberOrNull(rel.rot_sq_std_deg2);
}

void AddFileRelations(const std::vector<StampedPose>& est_poses, const EvalOptions& o, json& m) {
  if (o.relations.empty()) return;
  const RelationErrors e = ComputeRelationErrors(o.relations, est_poses, o.relation_matching);
  AddRelationMetric(ComputeRelationMetric(e.translation_m, e.rotation_deg), e.unmatched, m);
}

void AddTrajectoryMetrics(const Association& a, const std::vector<SE2>& est, const EvalOptions& o,
                          const AlignmentResult& umeyama, json& m, json& series) {
  const AbsoluteErrors ate = AbsoluteTrajectoryErrors(a.groundtruth, est);
  const std::vector<double> heading_deg = AbsDegrees(ate.heading_rad);
  AddStatistics(m, "ate", "_m", "_m2", ComputeStatistics(ate.translation_m));
  AddStatistics(m, "heading", "_deg", "_deg2", ComputeStatistics(heading_deg));
  ErrorStatistics aligned = ComputeStatistics({});
  if (umeyama.valid)
    aligned = ComputeStatistics(
        AbsoluteTrajectoryErrors(a.groundtruth, TransformPoses(umeyama.T_gt_est, a.estimate)).translation_m);
  AddStatistics(m, "ate_aligned", "_m", "_m2", aligned);
  m["alignment_valid"] = umeyama.valid;
  if (umeyama.valid) {
    m["alignment_se2"] = {umeyama.T_gt_est.x, umeyama.T_gt_est.y, umeyama.T_gt_est.theta * 180.0 / M_PI};
  } else {
    m["alignment_se2"] = nullptr;
    m["alignment_reason"] = umeyama.reason;
  }

  const RpeResult rpe = ComputeRpe(a.groundtruth, est, o.rpe);
  AddStatistics(m, "rpe_trans", "_m", "_m2", ComputeStatistics(rpe.translation_m));
  AddStatistics(m, "rpe_rot", "_deg", "_deg2", ComputeStatistics(rpe.rotation_deg));
  m["rpe_pairs"] = rpe.pairs.size();
  m["rpe_delta"] = o.rpe.delta;
  m["rpe_delta_unit"] = DeltaUnitName(o.rpe.unit);
  m["rpe_all_pairs"] = o.rpe.all_pairs;

  if (o.relations.empty()) AddRelationMetric(ComputeRelationMetric(rpe.translation_m, rpe.rotation_deg), nullptr, m);

  const KittiResult kitti = KittiSegmentErrors(a.groundtruth, est, o.kitti);
  m["kitti_segments"] = kitti.segments;
  m["kitti_trans_percent"] = NumberOrNull(kitti.translation_percent);
  m["kitti_rot_deg_per_m"] = NumberOrNull(kitti.rotation_deg_per_m);

  series["t_s"] = NumberArray(a.t_s);
  series["distance_m"] = NumberArray(a.distance_m);
  series["ate_m"] = NumberArray(ate.translation_m);
  series["heading_error_deg"] = NumberArray(heading_deg);
  json r = {{"distance_m", json::array()}, {"trans_m", NumberArray(rpe.translation_m)},
            {"rot_deg", NumberArray(rpe.rotation_deg)}};
  for (const auto& [i, j] : rpe.pairs) r["distance_m"].push_back(NumberOrNull(a.distance_m[j]));
  series["rpe"] = r;
}

void AddConsistency(const Association& a, const Estimate& est, const EvalOptions& o, json& m, json& series) {
  std::vector<double> nees;
  json per_step = json::array();
  for (size_t k = 0; k < a.t_s.size(); ++k) {
    const PoseEstimate& p = est.trajectory[a.estimate_index[k]];
    const double v = p.has_covariance ? PoseNees(a.groundtruth[k], a.estimate[k], p.covariance) : kNaN;
    per_step.push_back(NumberOrNull(v));
    if (std::isfinite(v)) nees.push_back(v);
  }
  const NeesBand band = AneesBand(3, 1, o.nees_confidence);
  series["nees"] = per_step;
  series["nees_band_95"] = {band.lo, band.hi};
  const ErrorStatistics s = ComputeStatistics(nees);
  m["anees"] = NumberOrNull(s.mean);
  m["nees_steps"] = s.count;
  m["nees_in_band_fraction"] = NumberOrNull(FractionInside(nees, band));
}

void AddLandmarks(const GroundTruth& gt, const Estimate& est, const EvalOptions& o, const AlignmentResult& umeyama,
                  json& m, json& series) {
  series["landmarks"] = json::array();
  const char* keys[] = {"landmark_rmse_m", "landmark_ospa_m", "landmark_spurious", "landmark_missed",
                        "landmark_anees",  "landmark_matched", "landmark_matching"};
  for (const char* k : keys) m[k] = nullptr;
  if (gt.trajectory.empty()) return;  // no ground truth (a converted log): nothing to compare with
  if (est.landmarks.empty() && gt.world.landmarks.empty()) return;
  if (est.landmarks.empty()) {  // a module without a landmark map: not applicable
    return;
  }
  const SE2 T = umeyama.valid ? umeyama.T_gt_est : SE2();
  const LandmarkMapResult r = EvaluateLandmarkMap(est.landmarks, gt.world.landmarks, T, o.landmarks);
  m["landmark_rmse_m"] = NumberOrNull(r.rmse_m);
  m["landmark_ospa_m"] = NumberOrNull(r.ospa_m);
  m["landmark_spurious"] = r.spurious;
  m["landmark_missed"] = r.missed;
  m["landmark_anees"] = NumberOrNull(r.anees);
  m["landmark_matched"] = r.matches.size();
  m["landmark_matching"] = r.by_id ? "id" : "optimal";
  for (const auto& match : r.matches)
    series["landmarks"].push_back({{"id", est.landmarks[match.estimate_index].id},
                                   {"true_id", gt.world.landmarks[match.true_index].id},
                                   {"error_m", NumberOrNull(match.error_m)},
                                   {"nees", NumberOrNull(match.nees)}});
}

void AddMaps(const GroundTruth& gt, const Estimate& est, const EvalOptions& o, json& m) {
  const char* keys[] = {"grid_cell_error", "grid_known_cells", "grid_mean_nearest_occupied_m",
                        "grid_mean_truth_to_estimate_m"};
  for (const char* k : keys) m[k] = nullptr;
  if (gt.trajectory.empty()) return;  // no ground truth: the stream's world is empty, not the truth
  if (!est.grid || est.grid->width <= 0 || est.grid->height <= 0 || !(est.grid->resolution_m > 0.0)) return;
  const GridMapResult g = EvaluateGridMap(*est.grid, gt.world, o.grid);
  m["grid_cell_error"] = NumberOrNull(g.cell_error);
  m["grid_known_cells"] = g.known_cells;
  m["grid_mean_nearest_occupied_m"] = NumberOrNull(g.mean_nearest_occupied_m);
  m["grid_mean_truth_to_estimate_m"] = NumberOrNull(g.mean_truth_to_estimate_m);
}

void AddLoopClosures(const GroundTruth& gt, const Estimate& est, const EvalOptions& o, json& m) {
  const LoopClosureResult r = EvaluateLoopClosures(est.loop_closures, gt.trajectory, o.loop_closures);
  const bool any = !est.loop_closures.empty() || !est.pose_graph.nodes.empty();  // a graph-building module
  const bool truth = !gt.trajectory.empty();  // precision, recall and revisits need the true path
  m["loop_closures"] = any ? json(r.accepted) : json(nullptr);
  m["loop_closures_proposed"] = any ? json(r.proposed) : json(nullptr);
  m["loop_closure_precision"] = any && truth ? NumberOrNull(r.precision) : json(nullptr);
  m["loop_closure_recall"] = any && truth ? NumberOrNull(r.recall) : json(nullptr);
  m["revisit_episodes"] = truth ? json(r.revisit_episodes) : json(nullptr);
}

void AddCost(const GroundTruth& gt, const Estimate& est, json& m) {
  // The run's duration: the ground truth's span, or the estimate's for a real log without it.
  const double duration = !gt.trajectory.empty()    ? gt.trajectory.back().t_s - gt.trajectory.front().t_s
                          : !est.trajectory.empty() ? est.trajectory.back().t_s - est.trajectory.front().t_s
                                                    : 0.0;
  const CostResult c = ComputeCost(est.step_time_s, est.finish_time_s, duration);
  m["runtime_s"] = c.available ? NumberOrNull(c.runtime_s) : json(nullptr);
  m["realtime_factor"] = c.available ? NumberOrNull(c.realtime_factor) : json(nullptr);
  m["step_time_median_s"] = c.available ? NumberOrNull(c.step_median_s) : json(nullptr);
  m["step_time_p95_s"] = c.available ? NumberOrNull(c.step_p95_s) : json(nullptr);
  m["step_time_max_s"] = c.available ? NumberOrNull(c.step_max_s) : json(nullptr);
}
}  // namespace

double PathLength(const std::vector<StampedPose>& trajectory) {
  double length = 0.0;
  for (size_t i = 1; i < trajectory.size(); ++i)
    length += (trajectory[i].pose.translation() - trajectory[i - 1].pose.translation()).norm();
  return length;
}

Evaluation EvaluateEstimate(const GroundTruth& gt, const Estimate& est, const EvalOptions& o) {
  Evaluation out;
  json& m = out.metrics;
  json& series = out.series;
  // Poses that are not finite are left out of the error metrics (divergence reports them).
  std::vector<StampedPose> est_poses;
  std::vector<int> original_index;
  for (size_t i = 0; i < est.trajectory.size(); ++i)
    if (Finite(est.trajectory[i].pose)) {
      est_poses.push_back({est.trajectory[i].t_s, est.trajectory[i].pose});
      original_index.push_back(static_cast<int>(i));
    }
  Association a = Associate(gt.trajectory, est_poses,
                            AssociationOptions{.max_time_diff_s = o.max_time_diff_s,
                                               .interpolate = o.interpolate_groundtruth});
  for (int& i : a.estimate_index) i = original_index[i];
  m["matched_poses"] = a.t_s.size();
  m["distance_m"] = PathLength(gt.trajectory);

  const AlignmentResult umeyama = UmeyamaAlignment(a.estimate, a.groundtruth);
  const std::vector<SE2> est_aligned = AlignedEstimate(a, o.align, umeyama);
  AddTrajectoryMetrics(a, est_aligned, o, umeyama, m, series);
  AddFileRelations(est_poses, o, m);
  AddConsistency(a, est, o, m, series);
  AddLandmarks(gt, est, o, umeyama, m, series);
  AddMaps(gt, est, o, m);
  AddLoopClosures(gt, est, o, m);
  AddCost(gt, est, m);

  const DivergenceResult div = DetectDivergence(est.trajectory, a.estimate_index,
                                                AbsoluteTrajectoryErrors(a.groundtruth, est_aligned).translation_m,
                                                a.distance_m, o.divergence);
  if (div.diverged) {
    m["status"] = "diverged";
    m["reason"] = div.reason;
  } else if (gt.trajectory.empty() && !est.trajectory.empty()) {  // a real log: nothing to compare with
    m["status"] = "ok";
    m["note"] = "the stream has no ground truth (a converted log): pose and map errors are null";
  } else if (a.t_s.empty()) {
    m["status"] = "failed";
    m["reason"] = est.trajectory.empty() ? "the estimate has no pose"
                                         : "no estimated pose matches a ground-truth timestamp within " +
                                               std::to_string(o.max_time_diff_s) + " s";
  } else {
    m["status"] = "ok";
  }
  return out;
}

}  // namespace slambox
