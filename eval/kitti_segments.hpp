#pragma once
// KITTI odometry devkit metric (Geiger et al. 2012, evaluate_odometry.cpp): from every
// step_frames-th pose, for each length L in lengths_m, the segment ends at the first pose
// whose ground-truth path distance exceeds the start's by more than L. Its error is
// E = (P_first^-1 P_last)^-1 (Q_first^-1 Q_last); translational error |t(E)| / L,
// rotational error |angle(E)| / L. The result is the mean over all segments, reported as
// percent and deg/m like the KITTI table.
#include <vector>

#include "core/se2.hpp"

namespace slambox {

struct KittiOptions {
  std::vector<double> lengths_m = {100, 200, 300, 400, 500, 600, 700, 800};
  int step_frames = 10;  ///< devkit: every 10th frame (1 s at KITTI's 10 Hz)
};

struct KittiResult {
  int segments = 0;
  double translation_percent = 0.0;  ///< NaN when no segment fits in the run
  double rotation_deg_per_m = 0.0;   ///< NaN when no segment fits in the run
};

KittiResult KittiSegmentErrors(const std::vector<SE2>& gt, const std::vector<SE2>& est,
                               const KittiOptions& options = {});

}  // namespace slambox
