#include "slam/adaptive_threshold.hpp"

#include <algorithm>
#include <cmath>

namespace slambox {

double ModelDeviation(const SE2& T, double max_range_m) {
  return 2.0 * max_range_m * std::sin(std::abs(T.theta) / 2.0) + T.translation().norm();
}

void UpdateThreshold(AdaptiveThreshold& threshold, const SE2& predicted_motion, const SE2& registered_motion) {
  // KISS-ICP skips near-standstill samples: they say nothing about the motion model.
  if (ModelDeviation(predicted_motion, threshold.config.max_range_m) < threshold.config.min_motion_m) return;
  const double dev = ModelDeviation(predicted_motion.inverse() * registered_motion, threshold.config.max_range_m);
  threshold.sum_sq_m2 += dev * dev;
  ++threshold.samples;
}

double CorrespondenceGate(const AdaptiveThreshold& threshold) {
  if (threshold.samples == 0) return threshold.config.initial_gate_m;
  const double sigma = std::sqrt(threshold.sum_sq_m2 / threshold.samples);
  return std::clamp(3.0 * sigma, threshold.config.min_gate_m, threshold.config.max_gate_m);
}

}  // namespace slambox
