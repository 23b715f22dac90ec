#include "slam/particle_weights.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cassert>
#include <cmath>

namespace slambox {

std::vector<double> NormalizeLogWeights(const std::vector<double>& log_weights) {
  assert(!log_weights.empty());
  const double max_log = *std::max_element(log_weights.begin(), log_weights.end());
  std::vector<double> w(log_weights.size());
  double sum = 0.0;
  for (size_t i = 0; i < w.size(); ++i) sum += (w[i] = std::exp(log_weights[i] - max_log));
  for (double& wi : w) wi /= sum;
  return w;
}

double EffectiveSampleSize(const std::vector<double>& weights) {
  double sum_sq = 0.0;
  for (double w : weights) sum_sq += w * w;
  return 1.0 / sum_sq;
}

std::vector<int> LowVarianceResample(const std::vector<double>& weights, std::mt19937_64& rng) {
  const int m_count = static_cast<int>(weights.size());
  const double step = 1.0 / m_count;
  const double r = std::uniform_real_distribution<double>(0.0, step)(rng);
  std::vector<int> chosen;
  chosen.reserve(weights.size());
  double cumulative = weights[0];
  int i = 0;
  for (int m = 0; m < m_count; ++m) {
    const double u = r + m * step;
    while (u > cumulative && i + 1 < m_count) cumulative += weights[++i];
    chosen.push_back(i);
  }
  return chosen;
}

Eigen::Vector3d SampleGaussian(const Eigen::Vector3d& mean, const Eigen::Matrix3d& covariance,
                               std::mt19937_64& rng) {
  std::normal_distribution<double> n01(0.0, 1.0);
  const Eigen::Vector3d n(n01(rng), n01(rng), n01(rng));
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(covariance);
  const Eigen::Vector3d sd = eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  return mean + eig.eigenvectors() * sd.cwiseProduct(n);
}

}  // namespace slambox
