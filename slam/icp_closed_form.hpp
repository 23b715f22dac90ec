#pragma once
// Closed-form minimizers used inside ICP for fixed correspondences.
#include <Eigen/Core>
#include <span>

#include "core/se2.hpp"

namespace slambox {

/// Point-to-point: argmin_T sum_i w_i |T s_i - t_i|^2 (Arun/Umeyama without scale):
/// weighted centroids, SVD of the 2x2 cross-covariance H = sum w (s - s̄)(t - t̄)^T,
/// R = V U^T with the reflection guard diag(1, det(V U^T)). Needs >= 2 distinct pairs.
SE2 AlignPointToPoint(std::span<const Eigen::Vector2d> source, std::span<const Eigen::Vector2d> target,
                      std::span<const double> weights);

/// Point-to-line for fixed correspondences (Censi 2008, PLICP): the exact
/// argmin_{t, theta} sum_i w_i (n_i^T (R(theta) s_i + t - q_i))^2, not a linearization.
/// With x = (t, c, s) the cost is quadratic and c^2 + s^2 = 1 is the only constraint;
/// t is eliminated in closed form, leaving min_r r^T Q r - 2 h^T r on the unit circle,
/// whose global minimum has r = (Q - lambda I)^-1 h with the unique lambda < eig_min(Q)
/// where |r| = 1 (the trust-region secular equation; Censi solves the same condition as
/// a quartic). Translation directions the normals do not constrain keep `T_current`'s value.
SE2 AlignPointToLine(std::span<const Eigen::Vector2d> source, std::span<const Eigen::Vector2d> target,
                     std::span<const Eigen::Vector2d> target_normals, std::span<const double> weights,
                     const SE2& T_current);

/// The sums behind the point-to-line cost, with x = (t, r), r = (cos, sin):
/// cost = x^T [Saa Sab; Sab^T Sbb] x - 2 [ga; gb]^T x + const.
struct PointToLineSums {
  Eigen::Matrix2d Saa = Eigen::Matrix2d::Zero(), Sab = Eigen::Matrix2d::Zero(), Sbb = Eigen::Matrix2d::Zero();
  Eigen::Vector2d ga = Eigen::Vector2d::Zero(), gb = Eigen::Vector2d::Zero();
};
PointToLineSums AccumulatePointToLine(std::span<const Eigen::Vector2d> source,
                                      std::span<const Eigen::Vector2d> target,
                                      std::span<const Eigen::Vector2d> target_normals,
                                      std::span<const double> weights);
/// The exact minimizer above, from the sums.
SE2 SolvePointToLine(const PointToLineSums& sums, const SE2& T_current);
/// Gauss-Newton Hessian over additive (t_x, t_y, theta) at theta: J_i = [n^T, b_i^T r_perp]
/// with r_perp = dr/dtheta, so H = [Saa, Sab r_perp; ., r_perp^T Sbb r_perp].
Eigen::Matrix3d PointToLineHessian(const PointToLineSums& sums, double theta_rad);

}  // namespace slambox
