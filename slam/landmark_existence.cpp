#include "slam/landmark_existence.hpp"

#include <Eigen/LU>
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

const EnumNames<ExistenceRule>& ExistenceRuleNames() {
  static const EnumNames<ExistenceRule> names = {{ExistenceRule::kSequentialTest, "sprt"},
                                                 {ExistenceRule::kCounts, "counts"}};
  return names;
}

WaldThresholds MakeWaldThresholds(double alpha, double beta) {
  assert(alpha > 0 && alpha < 0.5 && beta > 0 && beta < 0.5);
  return {std::log((1.0 - beta) / alpha), std::log(beta / (1.0 - alpha))};
}

double ExpectedInGate(const Eigen::Matrix2d& C, double gate_chi2, double density_per_m2) {
  return density_per_m2 * M_PI * gate_chi2 * std::sqrt(std::max(0.0, C.determinant()));
}

double ExpectedFalseInGate(const Eigen::Matrix2d& S, double range_m, double gate_chi2, double density_per_m2) {
  return ExpectedInGate(S, gate_chi2, density_per_m2) * range_m;
}

double DetectedLogRatio(double p_detect, double p_gate, double mu) {
  return ClampedLogRatio(std::clamp(p_detect, 0.0, 1.0) * p_gate, -std::expm1(-std::max(0.0, mu)));
}

double MissedLogRatio(double p_detect, double p_gate, double mu) {
  return ClampedLogRatio(1.0 - std::clamp(p_detect, 0.0, 1.0) * p_gate, std::exp(-std::max(0.0, mu)));
}

double NewLandmarkPriorLogRatio(double births, double scans, double clutter_per_scan) {
  const double n = births, clutter = clutter_per_scan * scans;
  const double p_real = std::clamp((n - clutter + 1.0) / (n + 2.0), 1.0 / (n + 2.0), (n + 1.0) / (n + 2.0));
  return std::log(p_real / (1.0 - p_real));
}

double UnmappedLandmarkDensity(double births, double scans, double clutter_per_scan, double footprint_m2,
                               double prior_scans) {
  return (std::max(0.0, births - clutter_per_scan * scans) + prior_scans) / ((scans + prior_scans) * footprint_m2);
}

}  // namespace slambox
