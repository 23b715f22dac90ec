#include "slam/landmark_existence.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace slambox {

namespace {
/// log(p1 / p0) clamped to +-kMaxTrialLogRatio; 0 if neither hypothesis allows the outcome.
double ClampedLogRatio(double p1, double p0) {
  if (!(p1 > 0) && !(p0 > 0)) return 0.0;
  if (!(p1 > 0)) return -kMaxTrialLogRatio;
  if (!(p0 > 0)) return kMaxTrialLogRatio;
  return std::clamp(std::log(p1) - std::log(p0), -kMaxTrialLogRatio, kMaxTrialLogRatio);
}
}  // namespace

WaldThresholds MakeWaldThresholds(double alpha, double beta) {
  assert(alpha > 0 && alpha < 0.5 && beta > 0 && beta < 0.5);
  return {std::log((1.0 - beta) / alpha), std::log(beta / (1.0 - alpha))};
}

double DetectedLogRatio(double p_detect, double p_gate, double mu) {
  return ClampedLogRatio(std::clamp(p_detect, 0.0, 1.0) * p_gate, -std::expm1(-std::max(0.0, mu)));
}

double MissedLogRatio(double p_detect, double p_gate, double mu) {
  return ClampedLogRatio(1.0 - std::clamp(p_detect, 0.0, 1.0) * p_gate, std::exp(-std::max(0.0, mu)));
}

double UnmappedLandmarkDensity(double births, double scans, double clutter_per_scan, double footprint_m2,
                               double prior_scans) {
  return (std::max(0.0, births - clutter_per_scan * scans) + prior_scans) / ((scans + prior_scans) * footprint_m2);
}

}  // namespace slambox
