#pragma once
// How big a scenario's simulation gets, known before simulating: the number of steps,
// events and readings, and the memory of the stream they make (the dominant term of the
// memory of `simulate` and `run`, which hold one stream). `slambox scenario show` prints
// it; LoadScenario refuses a scenario over the limits of core/limits.hpp.
#include <cstdint>
#include <string>

#include "sim/scenario.hpp"
#include "sim/simulate.hpp"

namespace slambox {

struct StreamSizeEstimate {
  double duration_s = 0.0;             ///< duration_s, or the simulator's cap when 0 (until the path ends)
  std::uint64_t steps = 0;             ///< simulator steps (ground-truth poses)
  std::uint64_t events = 0;            ///< sensor events of every sensor
  std::uint64_t laser_readings = 0;    ///< scans x beams
  std::uint64_t landmark_observations = 0;  ///< upper bound: scans x (posts + clutter mean)
  std::uint64_t bytes = 0;             ///< memory of the Stream in RAM (upper bound)
};

/// An upper bound on the stream's size: every sensor fires at its rate for the whole
/// duration (never more often than once a step), every post is seen in every scan.
///   bytes = events * sizeof(SensorEvent) + laser_readings * 9
///         + landmark_observations * sizeof(LandmarkObservation) + steps * sizeof(StampedPose)
StreamSizeEstimate EstimateStreamSize(const Scenario& scenario, const SimulationOptions& options = {});

/// One line per quantity, e.g. "stream: 30000 steps, 18000 events, ... ~ 12.3 MB".
std::string DescribeStreamSize(const StreamSizeEstimate& estimate);

}  // namespace slambox
