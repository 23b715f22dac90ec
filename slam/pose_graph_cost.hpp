#pragma once
// The 2D pose graph's edge cost for Ceres (after Ceres' examples/slam/pose_graph_2d's
// error term), with analytic Jacobians.
#include <ceres/sized_cost_function.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <type_traits>

#include "core/se2.hpp"

namespace slambox {

/// Whitened edge residual r = U e with U^T U = Omega (U upper-triangular Cholesky factor),
/// so |r|^2 = e^T Omega e. Parameter blocks: pose_i = (x [m], y [m], theta [rad]), pose_j.
class PoseGraphEdgeCost final : public ceres::SizedCostFunction<3, 3, 3> {
 public:
  PoseGraphEdgeCost(const SE2& T_ij, const Eigen::Matrix3d& sqrt_information)
      : T_ij_(T_ij), sqrt_information_(sqrt_information) {}

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;

 private:
  SE2 T_ij_;
  Eigen::Matrix3d sqrt_information_;
};

/// Upper-triangular U with U^T U = information (any square size: pose edges 3x3, landmark
/// edges 2x2); returns false unless information is symmetric positive definite and finite.
/// N comes from the output (the input may be an expression).
template <int N>
bool SqrtInformation(const std::type_identity_t<Eigen::Matrix<double, N, N>>& information,
                     Eigen::Matrix<double, N, N>* sqrt_information) {
  if (!information.allFinite()) return false;
  if (!information.isApprox(information.transpose(), 1e-12)) return false;
  const Eigen::LLT<Eigen::Matrix<double, N, N>> llt(information);
  if (llt.info() != Eigen::Success) return false;
  const Eigen::Matrix<double, N, N> U = llt.matrixU();
  if (!(U.diagonal().array() > 0.0).all()) return false;
  *sqrt_information = U;
  return true;
}

}  // namespace slambox
