#pragma once
// Importance weights of a particle filter: normalization in log space, the effective
// sample size and low-variance (systematic) resampling (Thrun, Prob. Robotics, Table 4.4).
#include <Eigen/Core>
#include <random>
#include <vector>

namespace slambox {

/// exp(log_w - logsumexp(log_w)): normalized weights, safe for log weights of any scale.
std::vector<double> NormalizeLogWeights(const std::vector<double>& log_weights);

/// N_eff = 1 / sum w_i^2 for normalized weights (Liu 1996); M for uniform weights, 1 when
/// one particle holds all the weight.
double EffectiveSampleSize(const std::vector<double>& weights);

/// Low-variance resampling: one uniform draw r in [0, 1/M), then the particles at the
/// cumulative weights r + m/M, m = 0..M-1. Particle i is drawn floor(M w_i) or
/// ceil(M w_i) times and M w_i times in expectation. Returns the M chosen indices (sorted).
std::vector<int> LowVarianceResample(const std::vector<double>& weights, std::mt19937_64& rng);

/// A draw from N(mean, covariance) for a positive semi-definite covariance (eigen
/// decomposition, so a singular or zero covariance is fine).
Eigen::Vector3d SampleGaussian(const Eigen::Vector3d& mean, const Eigen::Matrix3d& covariance, std::mt19937_64& rng);

}  // namespace slambox
