#pragma once
// Benchmark support: position RMSE of a trajectory against a simulated stream's ground
// truth (every estimate time is a simulator step, so poses are looked up, not matched).
#include <cmath>
#include <vector>

#include "core/estimate.hpp"
#include "core/stream.hpp"

namespace slambox {

inline double PositionRmse(const std::vector<PoseEstimate>& trajectory, const Stream& s) {
  double sum = 0;
  for (const PoseEstimate& p : trajectory) {
    const SE2& gt = s.groundtruth.at(static_cast<size_t>(std::llround(p.t_s / s.header.dt_s))).pose;
    sum += (p.pose.translation() - gt.translation()).squaredNorm();
  }
  return std::sqrt(sum / trajectory.size());
}

}  // namespace slambox
