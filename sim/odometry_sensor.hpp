#pragma once
// Wheel odometry: the true motion since the previous odometry event, decomposed into
// (rot1, trans, rot2) and perturbed with Thrun's odometry model (Probabilistic Robotics,
// Table 5.6 / sample_motion_model_odometry): each part gets zero-mean Gaussian noise with
// the standard deviations of IncrementCovariance (core/odometry_model.hpp).
#include <cstdint>
#include <random>

#include "core/sensors.hpp"
#include "core/stream.hpp"

namespace slambox {

class OdometrySensor {
 public:
  OdometrySensor(const OdometryConfig& config, std::uint64_t seed, const SE2& T_world_start);
  OdometryEvent Measure(double t_s, const SE2& T_world_robot);
  /// The robot was teleported (kidnapped) from `from` to `to` without the wheels turning:
  /// the motion already accumulated since the last event is kept, the jump is not seen.
  void Teleport(const SE2& from, const SE2& to);

 private:
  OdometryConfig config_;
  SE2 T_world_last_;  ///< true pose at the previous event
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
};

/// One noisy sample of the increment `true_delta` (exposed for tests).
SE2 SampleOdometry(const SE2& true_delta, const std::array<double, 4>& alpha, std::mt19937_64& rng,
                   std::normal_distribution<double>& normal);

}  // namespace slambox
