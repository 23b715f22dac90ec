#pragma once
// Gyro: the body's true yaw rate plus a constant bias and white Gaussian noise.
// Configured in deg/s (GyroConfig), reported in rad/s.
#include <cstdint>
#include <random>

#include "core/sensors.hpp"
#include "core/stream.hpp"

namespace slambox {

class GyroSensor {
 public:
  GyroSensor(const GyroConfig& config, std::uint64_t seed);
  GyroEvent Measure(double t_s, double true_yaw_rate_rps);

 private:
  double bias_rps_;
  double sigma_rps_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
};

}  // namespace slambox
