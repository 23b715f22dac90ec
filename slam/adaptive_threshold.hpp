#pragma once
// KISS-ICP's adaptive correspondence gate (Vizzo et al. 2023, Sec. III-C): the spread of
// the model deviation — how far ICP moved a point at max range away from where the motion
// prediction put it — sets the gate: sigma = sqrt(mean(dev^2)), gate = 3 sigma.
#include "core/se2.hpp"

namespace slambox {

struct AdaptiveThresholdConfig {
  double initial_gate_m = 0.5;   ///< [m] gate until the first deviation sample
  double max_range_m = 30.0;     ///< [m] lever arm that turns a rotation error into a point displacement
  double min_motion_m = 0.01;    ///< [m] samples whose predicted motion is smaller are skipped
  double min_gate_m = 0.05;      ///< [m] never gate tighter than this (sensor noise)
  double max_gate_m = 2.0;       ///< [m] never gate wider than this
};

struct AdaptiveThreshold {
  AdaptiveThresholdConfig config;
  double sum_sq_m2 = 0.0;
  int samples = 0;
};

/// Point displacement at max range caused by the deviation: 2 r sin(|dtheta|/2) + |dt|.
double ModelDeviation(const SE2& T_prediction_correction, double max_range_m);
/// Adds a sample: the prediction (odometry) and the ICP correction of the same motion.
void UpdateThreshold(AdaptiveThreshold& threshold, const SE2& predicted_motion, const SE2& registered_motion);
/// The current gate [m] (3 sigma, clamped).
double CorrespondenceGate(const AdaptiveThreshold& threshold);

}  // namespace slambox
