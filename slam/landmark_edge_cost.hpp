#pragma once
// The pose-landmark edge of a 2D graph for Ceres, with analytic Jacobians: a point
// landmark l_j [m, world frame] observed from pose i as z (its position in the pose's
// frame; g2o's EdgeSE2PointXY, iSAM's Pose2d_Point2d_Factor):
//   e = R_i^T (l_j - t_i) - z,   chi2 = e^T Omega e.
#include <ceres/sized_cost_function.h>

#include <Eigen/Core>

#include "slam/pose_graph_cost.hpp"  // SqrtInformation

namespace slambox {

/// Whitened residual r = U e with U^T U = Omega (upper-triangular U), so |r|^2 = e^T Omega e.
/// Parameter blocks: pose_i = (x [m], y [m], theta [rad]), landmark_j = (x [m], y [m]).
class LandmarkEdgeCost final : public ceres::SizedCostFunction<2, 3, 2> {
 public:
  LandmarkEdgeCost(const Eigen::Vector2d& p_pose_landmark, const Eigen::Matrix2d& sqrt_information)
      : z_(p_pose_landmark), sqrt_information_(sqrt_information) {}

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override;
  const Eigen::Vector2d& Measurement() const { return z_; }

 private:
  Eigen::Vector2d z_;
  Eigen::Matrix2d sqrt_information_;
};

/// The error e above for pose (t_i, theta_i) and landmark l_j.
Eigen::Vector2d LandmarkEdgeError(const Eigen::Vector3d& pose, const Eigen::Vector2d& l_world, const Eigen::Vector2d& z);


}  // namespace slambox
