#include "slam/detection_rate.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace slambox {

namespace {
size_t Band(const DetectionRate& r, double range_m) {
  const double u = range_m / r.range_max_m * static_cast<double>(r.seen.size());
  return static_cast<size_t>(std::clamp(std::floor(u), 0.0, static_cast<double>(r.seen.size() - 1)));
}
}  // namespace

DetectionRate MakeDetectionRate(double range_max_m, int bands, double prior) {
  assert(range_max_m > 0 && bands >= 1 && prior >= 0 && prior <= 1);
  return {range_max_m, prior, std::vector<double>(static_cast<size_t>(bands), 0.0),
          std::vector<double>(static_cast<size_t>(bands), 0.0)};
}

void CountExpected(DetectionRate& rate, double range_m, bool detected) {
  const size_t b = Band(rate, range_m);
  rate.expected[b] += 1.0;
  if (detected) rate.seen[b] += 1.0;
}

double DetectionProbability(const DetectionRate& rate, double range_m) {
  const size_t b = Band(rate, range_m);
  return (rate.seen[b] + rate.prior) / (rate.expected[b] + 1.0);
}

}  // namespace slambox
