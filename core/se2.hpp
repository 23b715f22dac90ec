#pragma once
// The project's one SE(2) type. A pose T_a_b maps points from frame b into frame a:
// p_a = R(theta) p_b + t. Composition T_a_c = T_a_b * T_b_c.
#include <Eigen/Core>
#include <cmath>

namespace slambox {

/// Wraps an angle to [-pi, pi) (Ceres pose_graph_2d's NormalizeAngle convention).
inline double NormalizeAngle(double angle_rad) {
  const double two_pi = 2.0 * M_PI;
  return angle_rad - two_pi * std::floor((angle_rad + M_PI) / two_pi);
}

inline Eigen::Matrix2d RotationMatrix(double theta_rad) {
  const double c = std::cos(theta_rad), s = std::sin(theta_rad);
  Eigen::Matrix2d R;
  R << c, -s, s, c;
  return R;
}

struct SE2 {
  double x = 0.0;      ///< [m]
  double y = 0.0;      ///< [m]
  double theta = 0.0;  ///< [rad], kept in [-pi, pi) by every operation below

  SE2() = default;
  SE2(double x_m, double y_m, double theta_rad) : x(x_m), y(y_m), theta(NormalizeAngle(theta_rad)) {}
  static SE2 FromVector(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

  Eigen::Vector2d translation() const { return {x, y}; }
  Eigen::Matrix2d rotation() const { return RotationMatrix(theta); }
  Eigen::Vector3d vector() const { return {x, y, theta}; }

  SE2 operator*(const SE2& o) const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * o.x - s * o.y, y + s * o.x + c * o.y, theta + o.theta};
  }
  Eigen::Vector2d operator*(const Eigen::Vector2d& p) const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * p.x() - s * p.y(), y + s * p.x() + c * p.y()};
  }
  SE2 inverse() const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {-c * x - s * y, s * x - c * y, -theta};
  }
};

/// Relative pose of b seen from a: T_a_b = T_w_a^-1 * T_w_b.
inline SE2 Between(const SE2& T_w_a, const SE2& T_w_b) { return T_w_a.inverse() * T_w_b; }

/// Exponential map of se(2): xi = (v_x, v_y, omega) -> SE2 (exact, with the V matrix).
SE2 Exp(const Eigen::Vector3d& xi);
/// Logarithm, inverse of Exp for |theta| < pi.
Eigen::Vector3d Log(const SE2& T);

/// Jacobians of the composition C = A * B over (x, y, theta) coordinates:
/// dC = J_a dA + J_b dB, with J_a = [I, R_A (-b_y, b_x)^T; 0, 1] and J_b = diag(R_A, 1).
struct ComposeJacobians {
  Eigen::Matrix3d J_a;
  Eigen::Matrix3d J_b;
};
ComposeJacobians ComposeJacobian(const SE2& A, const SE2& B);

/// First-order covariance of A * B for independent A ~ (A, cov_a), B ~ (B, cov_b):
/// J_a cov_a J_a^T + J_b cov_b J_b^T.
Eigen::Matrix3d ComposeCovariance(const SE2& A, const Eigen::Matrix3d& cov_a, const SE2& B,
                                  const Eigen::Matrix3d& cov_b);

/// 3x3 adjoint: Ad(T) xi = Log(T Exp(xi) T^-1) to first order, for xi = (v_x, v_y, omega).
Eigen::Matrix3d Adjoint(const SE2& T);

}  // namespace slambox
