#include "eval/loop_closures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "eval/association.hpp"

namespace slambox {

std::vector<std::pair<double, double>> RevisitEpisodes(const std::vector<StampedPose>& gt,
                                                       const LoopClosureOptions& o) {
  std::vector<int> idx;  // samples every sample_spacing_m of travel
  std::vector<double> dist;
  double travelled = 0.0, since_sample = 0.0;
  for (size_t i = 0; i < gt.size(); ++i) {
    if (i > 0) {
      const double step = (gt[i].pose.translation() - gt[i - 1].pose.translation()).norm();
      travelled += step;
      since_sample += step;
    }
    if (i == 0 || since_sample >= o.sample_spacing_m) {
      idx.push_back(static_cast<int>(i));
      dist.push_back(travelled);
      since_sample = 0.0;
    }
  }
  const size_t n = idx.size();
  std::vector<char> revisit(n, 0);
  for (size_t k = 0; k < n; ++k)
    for (size_t m = 0; m < k && dist[k] - dist[m] >= o.min_revisit_travel_m; ++m)
      if ((gt[idx[k]].pose.translation() - gt[idx[m]].pose.translation()).norm() <= o.revisit_radius_m) {
        revisit[k] = 1;
        break;
      }
  std::vector<std::pair<double, double>> episodes;
  for (size_t k = 0; k < n; ++k) {
    if (!revisit[k] || (k > 0 && revisit[k - 1])) continue;
    size_t end = k;
    while (end + 1 < n && revisit[end + 1]) ++end;
    const double t0 = gt[idx[k > 0 ? k - 1 : k]].t_s;
    const double t1 = gt[idx[end + 1 < n ? end + 1 : end]].t_s;
    episodes.emplace_back(t0, t1);
  }
  return episodes;
}

LoopClosureResult EvaluateLoopClosures(const std::vector<LoopClosureRecord>& closures,
                                       const std::vector<StampedPose>& gt, const LoopClosureOptions& o) {
  LoopClosureResult r;
  r.proposed = static_cast<int>(closures.size());
  std::vector<double> correct_times;
  for (const auto& c : closures) {
    SE2 Q_from, Q_to;
    int lower = 0;
    double u = 0.0;
    bool ok = InterpolatePose(gt, c.t_from_s, Q_from, lower, u) && InterpolatePose(gt, c.t_to_s, Q_to, lower, u);
    if (ok) {
      const SE2 T_true = Between(Q_from, Q_to);
      const Eigen::Vector2d t_err = T_true.rotation().transpose() * (c.T_from_to.translation() - T_true.translation());
      const double rot_err_deg = std::abs(NormalizeAngle(c.T_from_to.theta - T_true.theta)) * 180.0 / M_PI;
      ok = t_err.norm() <= o.max_translation_error_m && rot_err_deg <= o.max_rotation_error_deg;
    }
    r.correct.push_back(ok ? 1 : 0);
    if (!c.accepted) continue;
    ++r.accepted;
    if (ok) {
      ++r.accepted_correct;
      correct_times.push_back(std::max(c.t_from_s, c.t_to_s));
    }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  r.precision = r.accepted ? static_cast<double>(r.accepted_correct) / r.accepted : nan;
  const auto episodes = RevisitEpisodes(gt, o);
  r.revisit_episodes = static_cast<int>(episodes.size());
  for (const auto& episode : episodes)
    if (std::any_of(correct_times.begin(), correct_times.end(),
                    [&](double t) { return t >= episode.first && t <= episode.second; }))
      ++r.recalled_episodes;
  r.recall = r.revisit_episodes ? static_cast<double>(r.recalled_episodes) / r.revisit_episodes : nan;
  return r;
}

}  // namespace slambox
