#pragma once
// The 2D pose graph's edge cost for Ceres (after Ceres' examples/slam/pose_graph_2d's
// error term), with analytic Jacobians.
#include <ceres/sized_cost_function.h>

#include <Eigen/Core>

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

/// Upper-triangular U with U^T U = information; returns false unless information is
/// symmetric positive definite and finite.
bool SqrtInformation(const Eigen::Matrix3d& information, Eigen::Matrix3d* sqrt_information);

}  // namespace slambox
