#include <chrono>

#include "core/slam_module.hpp"

namespace slambox {

Estimate Replay(SlamModule& module, const Stream& stream) {
  using Clock = std::chrono::steady_clock;
  std::vector<double> step_time_s;
  step_time_s.reserve(stream.events.size());
  module.Start(stream.header);
  for (const SensorEvent& event : stream.events) {
    const auto t0 = Clock::now();
    std::visit(
        [&](const auto& e) {
          using E = std::decay_t<decltype(e)>;
          if constexpr (std::is_same_v<E, OdometryEvent>) module.OnOdometry(e);
          else if constexpr (std::is_same_v<E, LaserScanEvent>) module.OnLaserScan(e);
          else if constexpr (std::is_same_v<E, LandmarkEvent>) module.OnLandmarks(e);
          else module.OnGyro(e);
        },
        event);
    step_time_s.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
  }
  const auto t0 = Clock::now();
  Estimate estimate = module.Finish();
  estimate.finish_time_s = std::chrono::duration<double>(Clock::now() - t0).count();
  estimate.step_time_s = std::move(step_time_s);
  return estimate;
}

}  // namespace slambox
