#include "eval/kitti_segments.hpp"

#include <cassert>
#include <cmath>
#include <limits>

#include "eval/association.hpp"

namespace slambox {

KittiResult KittiSegmentErrors(const std::vector<SE2>& gt, const std::vector<SE2>& est, const KittiOptions& o) {
  assert(gt.size() == est.size());
  KittiResult r;
  const std::vector<double> dist = CumulativeDistance(gt);
  const int n = static_cast<int>(gt.size());
  double t_sum = 0.0, r_sum = 0.0;
  for (int first = 0; first < n; first += std::max(1, o.step_frames)) {
    for (double len : o.lengths_m) {
      int last = -1;  // devkit lastFrameFromSegmentLength
      for (int i = first; i < n; ++i)
        if (dist[i] > dist[first] + len) {
          last = i;
          break;
        }
      if (last < 0) continue;
      const SE2 delta_gt = Between(gt[first], gt[last]);
      const SE2 delta_est = Between(est[first], est[last]);
      const SE2 E = delta_est.inverse() * delta_gt;
      t_sum += std::sqrt(E.x * E.x + E.y * E.y) / len;
      r_sum += std::abs(NormalizeAngle(delta_gt.theta - delta_est.theta)) / len;
      ++r.segments;
    }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  r.translation_percent = r.segments ? 100.0 * t_sum / r.segments : nan;
  r.rotation_deg_per_m = r.segments ? (180.0 / M_PI) * r_sum / r.segments : nan;
  return r;
}

}  // namespace slambox
