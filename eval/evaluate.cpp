#include "eval/evaluate.hpp"

#include <cmath>
#include <limits>

#include "eval/alignment.hpp"
#include "eval/association.hpp"
#include "eval/association_agreement.hpp"
#include "eval/ate.hpp"
#include "core/chi_square.hpp"
#include "eval/consistency.hpp"
#include "eval/cost.hpp"
#include "eval/relation_metric.hpp"
#include "eval/statistics.hpp"

namespace slambox {

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

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

// relation_* from a relations file (eval/relations.hpp); without one they come from the RPE pairs.
void AddFileRelations(const std::vector<StampedPose>& est_poses, const EvalOptions& o, Metrics& m) {
  if (o.relations.empty()) return;
  const RelationErrors e = ComputeRelationErrors(o.relations, est_poses, o.relation_matching);
  m.relation = ComputeRelationMetric(e.translation_m, e.rotation_deg);
  m.relation_unmatched = e.unmatched;
}

void AddTrajectoryMetrics(const Association& a, const std::vector<SE2>& est, const EvalOptions& o,
                          const AlignmentResult& umeyama, Metrics& m, ErrorSeries& series) {
  const AbsoluteErrors ate = AbsoluteTrajectoryErrors(a.groundtruth, est);
  const std::vector<double> heading_deg = AbsDegrees(ate.heading_rad);
  m.ate = ComputeStatistics(ate.translation_m);
  m.heading = ComputeStatistics(heading_deg);
  m.ate_aligned = ComputeStatistics({});
  if (umeyama.valid)
    m.ate_aligned = ComputeStatistics(
        AbsoluteTrajectoryErrors(a.groundtruth, TransformPoses(umeyama.T_gt_est, a.estimate)).translation_m);
  m.alignment_valid = umeyama.valid;
  if (umeyama.valid)
    m.alignment_se2 = std::array<double, 3>{umeyama.T_gt_est.x, umeyama.T_gt_est.y, umeyama.T_gt_est.theta * 180.0 / M_PI};
  else
    m.alignment_reason = umeyama.reason;

  const RpeResult rpe = ComputeRpe(a.groundtruth, est, o.rpe);
  m.rpe_trans = ComputeStatistics(rpe.translation_m);
  m.rpe_rot = ComputeStatistics(rpe.rotation_deg);
  m.rpe_pairs = rpe.pairs.size();
  m.rpe_delta = o.rpe.delta;
  m.rpe_delta_unit = DeltaUnitName(o.rpe.unit);
  m.rpe_all_pairs = o.rpe.all_pairs;
  if (o.relations.empty()) m.relation = ComputeRelationMetric(rpe.translation_m, rpe.rotation_deg);

  const KittiResult kitti = KittiSegmentErrors(a.groundtruth, est, o.kitti);
  m.kitti_segments = kitti.segments;
  m.kitti_trans_percent = kitti.translation_percent;
  m.kitti_rot_deg_per_m = kitti.rotation_deg_per_m;

  series.t_s = a.t_s;
  series.distance_m = a.distance_m;
  series.ate_m = ate.translation_m;
  series.heading_error_deg = heading_deg;
  series.rpe_trans_m = rpe.translation_m;
  series.rpe_rot_deg = rpe.rotation_deg;
  for (const auto& [i, j] : rpe.pairs) series.rpe_distance_m.push_back(a.distance_m[j]);
}

void AddConsistency(const Association& a, const Estimate& est, const EvalOptions& o, Metrics& m, ErrorSeries& series) {
  std::vector<double> nees;
  for (size_t k = 0; k < a.t_s.size(); ++k) {
    const PoseEstimate& p = est.trajectory[a.estimate_index[k]];
    const double v = p.has_covariance ? PoseNees(a.groundtruth[k], a.estimate[k], p.covariance) : kNaN;
    series.nees.push_back(v);
    if (std::isfinite(v)) nees.push_back(v);
  }
  const NeesBand band = AneesBand(3, 1, o.nees_confidence);
  series.nees_band_lo = band.lo;
  series.nees_band_hi = band.hi;
  const ErrorStatistics s = ComputeStatistics(nees);
  m.anees = s.mean;
  m.nees_steps = s.count;
  m.nees_in_band_fraction = FractionInside(nees, band);
}

void AddLandmarks(const GroundTruth& gt, const Estimate& est, const EvalOptions& o, const AlignmentResult& umeyama,
                  Metrics& m, ErrorSeries& series) {
  if (gt.trajectory.empty()) return;  // no ground truth (a converted log): nothing to compare with (null)
  // A module without a landmark map: not applicable (null). One that reported what it did with
  // the detections (observation_assignments) and kept no landmark mapped none: it missed every
  // true one (a sweep's averages must not skip its run as if it had no map).
  if (est.landmarks.empty() && est.observation_assignments.empty()) return;
  const SE2 T = umeyama.valid ? umeyama.T_gt_est : SE2();
  const LandmarkMapResult r = EvaluateLandmarkMap(est.landmarks, gt.world.landmarks, T, o.landmarks);
  m.landmark_rmse_m = r.rmse_m;
  m.landmark_ospa_m = r.ospa_m;
  m.landmark_spurious = r.spurious;
  m.landmark_missed = r.missed;
  m.landmark_anees = r.anees;
  m.landmark_matched = r.matches.size();
  m.landmark_matching = r.by_id ? "id" : "optimal";
  for (const auto& match : r.matches)
    series.landmarks.push_back({est.landmarks[match.estimate_index].id, gt.world.landmarks[match.true_index].id,
                                match.error_m, match.nees});
}

void AddAssociation(const GroundTruth& gt, const Estimate& est, Metrics& m) {
  const AssociationAgreement r = ScoreAssociation(gt.observation_ids, est.observation_assignments);
  if (!r.agreement) return;  // no true id, or a module that does not report assignments: null
  m.association_agreement = *r.agreement;
  m.association_duplicates = r.duplicates;
  m.association_misses = r.misses;
  m.association_unused = r.unused;
}

void AddMaps(const GroundTruth& gt, const Estimate& est, const EvalOptions& o, Metrics& m) {
  if (gt.trajectory.empty()) return;  // no ground truth: the stream's world is empty, not the truth
  if (!est.grid || est.grid->width <= 0 || est.grid->height <= 0 || !(est.grid->resolution_m > 0.0)) return;
  const GridMapResult g = EvaluateGridMap(*est.grid, gt.world, o.grid);
  m.grid_cell_error = g.cell_error;
  m.grid_known_cells = g.known_cells;
  m.grid_mean_nearest_occupied_m = g.mean_nearest_occupied_m;
  m.grid_mean_truth_to_estimate_m = g.mean_truth_to_estimate_m;
}

void AddLoopClosures(const GroundTruth& gt, const Estimate& est, const EvalOptions& o, Metrics& m) {
  const LoopClosureResult r = EvaluateLoopClosures(est.loop_closures, gt.trajectory, o.loop_closures);
  const bool truth = !gt.trajectory.empty();  // precision, recall and revisits need the true path
  if (truth) m.revisit_episodes = r.revisit_episodes;
  if (est.loop_closures.empty() && est.pose_graph.nodes.empty()) return;  // builds no graph: null
  m.loop_closures = r.accepted;
  m.loop_closures_proposed = r.proposed;
  if (!truth) return;
  m.loop_closure_precision = r.precision;
  m.loop_closure_recall = r.recall;
}

void AddCost(const GroundTruth& gt, const Estimate& est, Metrics& m) {
  // The run's duration: the ground truth's span, or the estimate's for a real log without it.
  const double duration = !gt.trajectory.empty()    ? gt.trajectory.back().t_s - gt.trajectory.front().t_s
                          : !est.trajectory.empty() ? est.trajectory.back().t_s - est.trajectory.front().t_s
                                                    : 0.0;
  const CostResult c = ComputeCost(est.step_time_s, est.finish_time_s, duration);
  if (!c.available) return;
  m.runtime_s = c.runtime_s;
  m.realtime_factor = c.realtime_factor;
  m.step_time_median_s = c.step_median_s;
  m.step_time_p95_s = c.step_p95_s;
  m.step_time_max_s = c.step_max_s;
}
}  // namespace

std::vector<std::vector<int>> ObservationIds(const Stream& stream) {
  std::vector<std::vector<int>> ids;
  for (const SensorEvent& e : stream.events)
    if (const auto* l = std::get_if<LandmarkEvent>(&e)) {
      std::vector<int>& scan = ids.emplace_back();
      for (const LandmarkObservation& o : l->observations) scan.push_back(o.id);
    }
  return ids;
}

double PathLength(const std::vector<StampedPose>& trajectory) {
  double length = 0.0;
  for (size_t i = 1; i < trajectory.size(); ++i)
    length += (trajectory[i].pose.translation() - trajectory[i - 1].pose.translation()).norm();
  return length;
}

double GroundTruthDistance(const std::vector<StampedPose>& groundtruth) {
  return groundtruth.empty() ? NAN : PathLength(groundtruth);
}

Evaluation EvaluateEstimate(const GroundTruth& gt, const Estimate& est, const EvalOptions& o) {
  Evaluation out;
  Metrics& m = out.metrics;
  ErrorSeries& series = out.series;
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
  m.matched_poses = a.t_s.size();
  m.distance_m = GroundTruthDistance(gt.trajectory);

  const AlignmentResult umeyama = UmeyamaAlignment(a.estimate, a.groundtruth);
  const std::vector<SE2> est_aligned = AlignedEstimate(a, o.align, umeyama);
  AddTrajectoryMetrics(a, est_aligned, o, umeyama, m, series);
  if (gt.trajectory.empty()) m.alignment_reason = "the stream has no ground truth";
  AddFileRelations(est_poses, o, m);
  AddConsistency(a, est, o, m, series);
  AddLandmarks(gt, est, o, umeyama, m, series);
  AddAssociation(gt, est, m);
  AddMaps(gt, est, o, m);
  AddLoopClosures(gt, est, o, m);
  AddCost(gt, est, m);

  const DivergenceResult div = DetectDivergence(est.trajectory, a.estimate_index,
                                                AbsoluteTrajectoryErrors(a.groundtruth, est_aligned).translation_m,
                                                a.distance_m, o.divergence);
  if (div.diverged) {
    m.status = RunStatus::kDiverged;
    m.reason = div.reason;
  } else if (gt.trajectory.empty() && !est.trajectory.empty()) {  // a real log: nothing to compare with
    m.status = RunStatus::kOk;
    m.note = "the stream has no ground truth (a converted log): pose and map errors are null";
  } else if (a.t_s.empty()) {
    m.status = RunStatus::kFailed;
    m.reason = est.trajectory.empty() ? "the estimate has no pose"
                                         : "no estimated pose matches a ground-truth timestamp within " +
                                               std::to_string(o.max_time_diff_s) + " s";
  } else {
    m.status = RunStatus::kOk;
  }
  return out;
}

}  // namespace slambox
