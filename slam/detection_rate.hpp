#pragma once
// The detector's detection probability as a function of range, estimated during the run
// from the module's own confirmed landmarks: in each range band, the fraction of scans
// that saw a landmark predicted in range and field of view. A real detector's P_D is
// rarely the configured one: Victoria Park's tree detector sees a tree in view in at most
// ~half of the scans (occlusion by other trees, trunk size), and almost never beyond 40 m,
// though its range reaches 79 m. The existence count uses it (EkfSlam::ManageExistence):
// a miss costs the detection that was expected, P_D(r) scaled by the landmark's own
// visibility, not one.
#include <vector>

namespace slambox {

struct DetectionRate {
  double range_max_m = 1.0;
  double prior = 1.0;        ///< the sensor's configured detection probability (one pseudo-scan)
  /// One band by default (DetectionProbability is then `prior` until counted).
  std::vector<double> seen = {0.0};      ///< per band: scans in which an expected landmark was detected
  std::vector<double> expected = {0.0};  ///< per band: scans in which a landmark was expected in view
};

/// `bands` equal range bands over [0, range_max_m); `prior` weighs as one scan per band.
DetectionRate MakeDetectionRate(double range_max_m, int bands, double prior);
/// Counts one scan in which a landmark was expected at `range_m`, `detected` or not.
void CountExpected(DetectionRate& rate, double range_m, bool detected);
/// (seen + prior) / (expected + 1) in the band of `range_m` (Laplace's rule with the
/// configured probability as the prior guess).
double DetectionProbability(const DetectionRate& rate, double range_m);

}  // namespace slambox
