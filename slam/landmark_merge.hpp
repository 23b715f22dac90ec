#pragma once
// Merging two EKF-SLAM landmarks that are one physical landmark. After drift a
// re-observed landmark can fall outside the association gates and be mapped a second
// time; once a loop closes (the map is corrected through other landmarks) the two
// estimates become statistically identical. For landmarks a and b the difference
// D = m_a - m_b has covariance C = P_aa + P_bb - P_ab - P_ba, and d^2 = D^T C^-1 D is
// chi-square with 2 dof if a and b are the same point. A merge conditions the whole
// state on m_a = m_b (a perfect relative measurement 0 = H x with H = [.. I .. -I ..]:
// K = P H^T C^-1, x' = x - K D, P' = P - K H P) and then marginalizes m_b out.
#include "slam/ekf_slam_filter.hpp"

namespace slambox {

/// The difference of two points stacked in a Gaussian (x, P) at rows ia and ib: D, its
/// covariance C and d^2 = D^T C^-1 D (infinity if C is not positive definite).
struct PointDifference {
  Eigen::Vector2d D = Eigen::Vector2d::Zero();
  Eigen::Matrix2d C = Eigen::Matrix2d::Zero();
  double d2 = 0.0;
};
PointDifference DifferenceOf(const Eigen::VectorXd& x, const Eigen::MatrixXd& P, Eigen::Index ia, Eigen::Index ib);

/// Conditions (x, P) on m_a = m_b, the points at rows ia and ib (see above). Returns false,
/// leaving them unchanged, if C is not positive definite.
bool ConditionOnEqual(Eigen::VectorXd& x, Eigen::MatrixXd& P, Eigen::Index ia, Eigen::Index ib);

/// d^2 = D^T C^-1 D of landmarks a and b (infinity if C is not positive definite).
double LandmarkDifferenceChi2(const EkfSlamState& state, int a, int b);

/// Conditions the state on m_keep = m_remove and removes landmark `remove` (later
/// indices shift down by one). Returns false, leaving the state unchanged, if C is not
/// positive definite.
bool MergeLandmarks(EkfSlamState& state, int keep, int remove);

}  // namespace slambox
