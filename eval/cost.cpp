#include "eval/cost.hpp"

#include <algorithm>
#include <limits>

#include "eval/statistics.hpp"

namespace slambox {

CostResult ComputeCost(const std::vector<double>& steps, double finish_time_s, double duration_s) {
  CostResult c;
  if (steps.empty()) return c;
  c.available = true;
  c.step_median_s = Percentile(steps, 50.0);
  c.step_p95_s = Percentile(steps, 95.0);
  c.step_max_s = *std::max_element(steps.begin(), steps.end());
  double total = finish_time_s;
  for (double s : steps) total += s;
  c.runtime_s = total;
  c.realtime_factor = total > 0.0 ? duration_s / total : std::numeric_limits<double>::infinity();
  return c;
}

}  // namespace slambox
