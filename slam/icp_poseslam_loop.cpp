// icp-poseslam's loop targets (submaps with the side each point was seen from), loop
// verification (TryLoop) and region search (CloseLoopInRegion, slam/loop_region.hpp); the rest
// of the module is in slam/icp_poseslam.cpp.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "slam/icp_poseslam.hpp"

namespace slambox {

namespace {
constexpr double kDegToRad = M_PI / 180.0;
}  // namespace

std::vector<Eigen::Vector2d> IcpPoseSlam::LoopSource() const {
  const int k = static_cast<int>(keyframes_.size()) - 1;
  std::vector<Eigen::Vector2d> source = keyframes_.back().points.points;
  // Older keyframes in the newest one's frame; their relative poses are the front end's
  // (no closure between them), accurate over the few metres this spans.
  for (int i = k - 1; i >= std::max(0, k - config_.loop_submap_keyframes) &&
                      static_cast<int>(source.size()) < config_.loop_min_source_points;
       --i) {
    const SE2 T_k_i = Between(graph_.poses.back(), graph_.poses[static_cast<size_t>(i)]);
    for (const auto& p : keyframes_[static_cast<size_t>(i)].points.points) source.push_back(T_k_i * p);
  }
  return source;
}

IcpPoseSlam::LoopSubmap IcpPoseSlam::LoopSubmapPoints(const std::vector<int>& ids, const SE2& T_w_frame,
                                                      const std::function<bool(const Eigen::Vector2d&)>& keep) const {
  std::vector<Eigen::Vector2d> points, sensors;  // sensors: where each point was seen from
  for (int i : ids) {
    const SE2 T_frame_i = Between(T_w_frame, graph_.poses[static_cast<size_t>(i)]);
    for (const auto& p : keyframes_[static_cast<size_t>(i)].points.points) {
      const Eigen::Vector2d q = T_frame_i * p;
      if (!keep || keep(q)) {
        points.push_back(q);
        sensors.push_back(T_frame_i.translation());
      }
    }
  }
  LoopSubmap out;
  for (int i : VoxelSubsample(points, 0.5 * config_.loop_table.resolution_m)) {
    out.points.push_back(points[static_cast<size_t>(i)]);
    out.viewpoints.push_back(sensors[static_cast<size_t>(i)]);
  }
  return out;
}

IcpTarget IcpPoseSlam::LoopCloud(LoopSubmap submap) {
  IcpTarget cloud = MakeCloudTarget(std::move(submap.points));
  OrientNormalsTowards(&cloud, submap.viewpoints);
  return cloud;
}

const IcpPoseSlam::LoopTarget& IcpPoseSlam::LoopTargetFor(int keyframe) {
  for (const LoopTarget& t : loop_targets_)
    if (t.keyframe == keyframe) return t;
  constexpr size_t kCached = 8;
  if (loop_targets_.size() >= kCached) loop_targets_.erase(loop_targets_.begin());
  const int n = static_cast<int>(keyframes_.size());
  std::vector<int> ids;
  for (int i = std::max(0, keyframe - config_.loop_submap_keyframes);
       i <= std::min(n - 1, keyframe + config_.loop_submap_keyframes); ++i)
    ids.push_back(i);
  LoopSubmap submap = LoopSubmapPoints(ids, graph_.poses[static_cast<size_t>(keyframe)], nullptr);
  LoopTarget t;
  t.keyframe = keyframe;
  t.table = MakeScoreTable(submap.points, config_.loop_table, submap.viewpoints);
  t.cloud = LoopCloud(std::move(submap));
  loop_targets_.push_back(std::move(t));
  return loop_targets_.back();
}

bool IcpPoseSlam::TryLoop(int from, const std::vector<Eigen::Vector2d>& source, const ScoreTable& table,
                          const std::function<const IcpTarget&()>& cloud, double radius_m, double angle_rad,
                          double* innovation_m) {
  const int k = static_cast<int>(keyframes_.size()) - 1;
  const SE2 guess = Between(graph_.poses[static_cast<size_t>(from)], graph_.poses.back());
  CorrelativeSearchConfig search;
  search.linear_window_m = radius_m;
  search.angular_window_deg = angle_rad / kDegToRad;
  search.min_score = config_.loop_min_score;
  search.runner_up_radius_m = config_.loop_runner_up_radius_m;
  const CorrelativeMatch m = MatchCorrelative(table, source, guess, search);
  ++proposed_;
  const double t_old = keyframes_[static_cast<size_t>(from)].t_s;
  // No match, an ambiguous one, or one on the window's edge (a window drawn from a graph that
  // is surer than it should be, e.g. along a corridor: the true pose lies beyond it).
  if (!m.found || m.runner_up_score >= config_.loop_max_runner_up_ratio * m.score ||
      (config_.loop_reject_window_edge && m.at_window_edge)) {
    estimate_.loop_closures.push_back({t_old, keyframes_.back().t_s, guess, false});
    return false;
  }
  const IcpResult r = RegisterIcp(source, cloud(), m.T_map_source, loop_icp_);
  LoopVerification v = VerifyLoopClosure(r, guess, radius_m + config_.loop_max_match_shift_m, config_.loop);
  if (v.accepted && (r.T_target_source.translation() - m.T_map_source.translation()).norm() > config_.loop_max_match_shift_m)
    v = {false, "icp left the correlative match"};
  if (v.accepted) {  // the new scan's own points: its sensor is at their origin
    const BackFaceResult b = BackFaces(keyframes_.back().points.points, cloud(), r.T_target_source, config_.loop_back_face);
    estimate_.diagnostics["loop_back_face_fraction"].emplace_back(keyframes_.back().t_s, b.fraction);
    if (b.fraction > config_.loop_max_back_face_fraction) v = {false, "the scan sees the target's surfaces from behind"};
  }
  estimate_.loop_closures.push_back({t_old, keyframes_.back().t_s, r.T_target_source, v.accepted});
  if (!v.accepted) return false;
  PoseGraphEdge e;
  e.from = from;
  e.to = k;
  e.T_from_to = r.T_target_source;
  e.information = config_.edge_information == EdgeInformationSource::kFixed
                      ? FixedInformation(config_.fixed_sigma_xy_m, config_.fixed_sigma_theta_deg * kDegToRad)
                      : IcpEdgeInformation(r, 1e6 * Eigen::Matrix3d::Identity(), Caps());
  e.loop_closure = true;
  graph_.edges.push_back(e);
  loop_record_of_edge_.push_back(static_cast<int>(estimate_.loop_closures.size()) - 1);
  *innovation_m = (r.T_target_source.translation() - guess.translation()).norm();
  return true;
}

bool IcpPoseSlam::CloseLoopInRegion(const std::vector<Eigen::Vector2d>& source,
                                    const std::vector<Eigen::Matrix3d>& relative_cov, const std::vector<double>& path,
                                    double* innovation_m) {
  const int k = static_cast<int>(keyframes_.size()) - 1;
  if (source.empty()) return false;
  // The scan's reach: the median range of its points (half of what it sees is closer).
  std::vector<double> ranges;
  for (const auto& p : source) ranges.push_back(p.norm());
  std::nth_element(ranges.begin(), ranges.begin() + static_cast<long>(ranges.size() / 2), ranges.end());
  const double reach_m = ranges[ranges.size() / 2];
  // Members: old keyframes (path gap >= min_travel) within reach + their window of the new one.
  const Eigen::Vector2d here = graph_.poses.back().translation();
  LoopClosureConfig window = config_.loop;
  if (config_.loop_region_max_search_radius_m > 0) window.max_search_radius_m = config_.loop_region_max_search_radius_m;
  // The robot's own trail is no loop: the keyframes since it was last outside the region
  // (farther than reach + window from here) are not members.
  auto in_reach = [&](int j, double* d, double* radius) {
    const size_t uj = static_cast<size_t>(j);
    *radius = LoopWindow(&relative_cov[uj], path[static_cast<size_t>(k)] - path[uj], window).first;
    *d = (graph_.poses[uj].translation() - here).norm();
    return *d <= reach_m + *radius;
  };
  int trail = k;
  for (double d, radius; trail > 0 && in_reach(trail - 1, &d, &radius);) --trail;
  std::vector<int> members;
  int anchor = -1;
  double anchor_d = std::numeric_limits<double>::infinity();
  for (int j = 0; j < trail; ++j) {
    double d = 0.0, radius = 0.0;
    if (path[static_cast<size_t>(k)] - path[static_cast<size_t>(j)] < config_.loop.min_travel_m || !in_reach(j, &d, &radius))
      continue;
    members.push_back(j);
    if (d < anchor_d) anchor_d = d, anchor = j;
  }
  if (members.empty()) return false;
  std::vector<const std::vector<Eigen::Vector2d>*> points_of(keyframes_.size(), nullptr);
  for (int j : members) points_of[static_cast<size_t>(j)] = &keyframes_[static_cast<size_t>(j)].points.points;
  RegionConfig rc = config_.loop_region_passes;
  rc.min_agreement = config_.loop_min_score;
  rc.sigma_m = config_.loop_table.sigma_m;
  const RegionSelection region = SelectConsistentPasses(graph_.poses, points_of, members, anchor, here, rc);
  auto& d = estimate_.diagnostics;
  const double t_s = keyframes_.back().t_s;
  d["loop_region_passes"].emplace_back(t_s, static_cast<double>(region.passes.size()));
  d["loop_region_passes_admitted"].emplace_back(t_s, region.admitted_passes);
  if (region.admitted_passes < config_.loop_region_min_passes) return false;
  // The target in the anchor's frame, cropped to where the new scan can land: the box of its
  // points at the guess, widened by the window and the score's reach (3 sigma).
  const auto [radius, angle] = LoopWindow(&relative_cov[static_cast<size_t>(anchor)],
                                          path[static_cast<size_t>(k)] - path[static_cast<size_t>(anchor)], window);
  const SE2& T_w_a = graph_.poses[static_cast<size_t>(anchor)];
  const SE2 guess = Between(T_w_a, graph_.poses.back());
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& p : source) {
    // Rotating by up to `angle` about the guess moves a point by at most 2 |p| sin(angle / 2).
    const Eigen::Vector2d q = guess * p;
    const double spread = 2.0 * p.norm() * std::sin(0.5 * angle);
    lo = lo.cwiseMin(q - Eigen::Vector2d::Constant(spread));
    hi = hi.cwiseMax(q + Eigen::Vector2d::Constant(spread));
  }
  const double margin = radius + 3.0 * config_.loop_table.sigma_m;
  lo.array() -= margin;
  hi.array() += margin;
  const LoopSubmap submap = LoopSubmapPoints(region.keyframes, T_w_a, [&](const Eigen::Vector2d& q) {
    return (q.array() >= lo.array()).all() && (q.array() <= hi.array()).all();
  });
  if (submap.points.empty()) return false;
  // With loop_table_unknown_score > 0 the rays of points cropped out above are not traced:
  // the free space only they crossed counts as unobserved.
  const ScoreTable table = MakeScoreTable(submap.points, config_.loop_table, submap.viewpoints);
  std::optional<IcpTarget> cloud;  // built only when the correlative match passes
  const bool added = TryLoop(anchor, source, table, [&]() -> const IcpTarget& {
    if (!cloud) cloud = LoopCloud(submap);
    return *cloud;
  }, radius, angle, innovation_m);
  d["loop_region_searches"].emplace_back(t_s, 1.0);
  if (added) d["loop_region_closures"].emplace_back(t_s, static_cast<double>(anchor));
  return added;
}

}  // namespace slambox
