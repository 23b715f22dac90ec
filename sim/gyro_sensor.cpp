#include "sim/gyro_sensor.hpp"

#include <cmath>

#include "sim/seeding.hpp"

namespace slambox {

GyroSensor::GyroSensor(const GyroConfig& config, std::uint64_t seed)
    : bias_rps_(config.bias_dps * M_PI / 180.0),
      sigma_rps_(config.sigma_dps * M_PI / 180.0),
      rng_(MakeGenerator(seed, NoiseSource::kGyro)) {}

GyroEvent GyroSensor::Measure(double t_s, double true_yaw_rate_rps) {
  return {t_s, true_yaw_rate_rps + bias_rps_ + sigma_rps_ * normal_(rng_)};
}

}  // namespace slambox
