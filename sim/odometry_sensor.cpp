#include "sim/odometry_sensor.hpp"

#include <cmath>

#include "core/odometry_model.hpp"
#include "sim/seeding.hpp"

namespace slambox {

SE2 SampleOdometry(const SE2& true_delta, const std::array<double, 4>& alpha, std::mt19937_64& rng,
                   std::normal_distribution<double>& normal) {
  OdometryIncrement u = Decompose(true_delta);
  const Eigen::Matrix3d M = IncrementCovariance(u, alpha);
  u.rot1 += std::sqrt(M(0, 0)) * normal(rng);
  u.trans += std::sqrt(M(1, 1)) * normal(rng);
  u.rot2 += std::sqrt(M(2, 2)) * normal(rng);
  return Compose(u);
}

OdometrySensor::OdometrySensor(const OdometryConfig& config, std::uint64_t seed, const SE2& T_world_start)
    : config_(config), T_world_last_(T_world_start), rng_(MakeGenerator(seed, NoiseSource::kOdometry)) {}

OdometryEvent OdometrySensor::Measure(double t_s, const SE2& T_world_robot) {
  const SE2 delta = Between(T_world_last_, T_world_robot);
  T_world_last_ = T_world_robot;
  return {t_s, SampleOdometry(delta, config_.alpha, rng_, normal_)};
}

void OdometrySensor::Teleport(const SE2& from, const SE2& to) { T_world_last_ = to * Between(from, T_world_last_); }

}  // namespace slambox
