#pragma once
// Processing cost of a SLAM module from the wall times Replay measured per stream event
// (Estimate::step_time_s) and for Finish() (finish_time_s).
#include <vector>

namespace slambox {

struct CostResult {
  bool available = false;      ///< false without step times (e.g. a TUM file)
  double step_median_s = 0.0;
  double step_p95_s = 0.0;     ///< numpy percentile, linear interpolation
  double step_max_s = 0.0;
  double runtime_s = 0.0;      ///< sum of step times + finish time
  double realtime_factor = 0.0;  ///< data duration / runtime_s; inf for zero runtime
};

CostResult ComputeCost(const std::vector<double>& step_time_s, double finish_time_s, double data_duration_s);

}  // namespace slambox
