#include "eval/association.hpp"

#include <algorithm>
#include <cmath>

namespace slambox {

namespace {
// Index of the nearest stamp in sorted `stamps` to t (numpy argmin of |stamps - t|: the
// first index on ties).
size_t NearestIndex(const std::vector<double>& stamps, double t) {
  const auto it = std::lower_bound(stamps.begin(), stamps.end(), t);
  size_t j = static_cast<size_t>(it - stamps.begin());
  if (j == stamps.size()) return j - 1;
  if (j == 0) return 0;
  return std::abs(stamps[j - 1] - t) <= std::abs(stamps[j] - t) ? j - 1 : j;
}

std::vector<double> Stamps(const std::vector<StampedPose>& poses) {
  std::vector<double> t;
  t.reserve(poses.size());
  for (const auto& p : poses) t.push_back(p.t_s);
  return t;
}

std::vector<SE2> Poses(const std::vector<StampedPose>& poses) {
  std::vector<SE2> out;
  out.reserve(poses.size());
  for (const auto& p : poses) out.push_back(p.pose);
  return out;
}
}  // namespace

std::vector<double> CumulativeDistance(const std::vector<SE2>& poses) {
  std::vector<double> d(poses.size(), 0.0);
  for (size_t i = 1; i < poses.size(); ++i) {
    const double dx = poses[i].x - poses[i - 1].x, dy = poses[i].y - poses[i - 1].y;
    d[i] = d[i - 1] + std::sqrt(dx * dx + dy * dy);  // numpy's norm, summed in order (cumsum)
  }
  return d;
}

bool InterpolatePose(const std::vector<StampedPose>& traj, double t_s, SE2& pose, int& lower_index,
                     double& fraction) {
  if (traj.empty() || t_s < traj.front().t_s || t_s > traj.back().t_s) return false;
  const auto it = std::lower_bound(traj.begin(), traj.end(), t_s,
                                   [](const StampedPose& p, double t) { return p.t_s < t; });
  const size_t j = static_cast<size_t>(it - traj.begin());
  if (traj[j].t_s == t_s) {  // exact stamp: no arithmetic, so identical inputs stay identical
    pose = traj[j].pose;
    lower_index = static_cast<int>(j);
    fraction = 0.0;
    return true;
  }
  const SE2& a = traj[j - 1].pose;
  const SE2& b = traj[j].pose;
  const double u = (t_s - traj[j - 1].t_s) / (traj[j].t_s - traj[j - 1].t_s);
  pose = SE2(a.x + u * (b.x - a.x), a.y + u * (b.y - a.y), a.theta + u * NormalizeAngle(b.theta - a.theta));
  lower_index = static_cast<int>(j - 1);
  fraction = u;
  return true;
}

Association Associate(const std::vector<StampedPose>& gt, const std::vector<StampedPose>& est,
                      const AssociationOptions& options) {
  Association out;
  if (gt.empty() || est.empty()) return out;
  const std::vector<double> gt_distance = CumulativeDistance(Poses(gt));
  auto add = [&](size_t i_est, const SE2& gt_pose, double distance_m) {
    out.t_s.push_back(est[i_est].t_s);
    out.groundtruth.push_back(gt_pose);
    out.estimate.push_back(est[i_est].pose);
    out.estimate_index.push_back(static_cast<int>(i_est));
    out.distance_m.push_back(distance_m);
  };
  if (options.interpolate) {
    for (size_t i = 0; i < est.size(); ++i) {
      SE2 pose;
      int lower = 0;
      double u = 0.0;
      if (!InterpolatePose(gt, est[i].t_s, pose, lower, u)) continue;
      const double d0 = gt_distance[lower];
      add(i, pose, u == 0.0 ? d0 : d0 + u * (gt_distance[lower + 1] - d0));
    }
    return out;
  }
  // evo: traj_1 = reference, traj_2 = estimate; the estimate is walked unless it is longer.
  const bool est_longer = est.size() > gt.size();
  if (!est_longer) {
    const std::vector<double> stamps = Stamps(gt);
    for (size_t i = 0; i < est.size(); ++i) {
      const size_t j = NearestIndex(stamps, est[i].t_s);
      if (std::abs(stamps[j] - est[i].t_s) <= options.max_time_diff_s) add(i, gt[j].pose, gt_distance[j]);
    }
  } else {
    const std::vector<double> stamps = Stamps(est);
    for (size_t j = 0; j < gt.size(); ++j) {
      const size_t i = NearestIndex(stamps, gt[j].t_s);
      if (std::abs(stamps[i] - gt[j].t_s) <= options.max_time_diff_s) add(i, gt[j].pose, gt_distance[j]);
    }
  }
  return out;
}

}  // namespace slambox
