#pragma once
// Rigid alignment of an estimated trajectory to ground truth.
// SE(2) Umeyama (Umeyama 1991, eqs. 34-43, scale fixed to 1), as evo's
// geometry.umeyama_alignment in two dimensions: means, cross-covariance
// Sigma_xy = 1/n sum (y_i - mu_y)(x_i - mu_x)^T, SVD Sigma_xy = U D V^T,
// S = diag(1, det(U) det(V)) (the reflection fix), R = U S V^T, t = mu_y - R mu_x.
// Alignment to the origin, as evo's align_origin: T = Q_0 P_0^-1.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/se2.hpp"

namespace slambox {

struct AlignmentResult {
  bool valid = false;
  SE2 T_gt_est;        ///< maps estimate poses into the ground-truth frame: Q ~ T P
  std::string reason;  ///< why not valid
};

/// Least-squares rotation and translation taking the estimate positions onto the ground
/// truth positions (same length, index-matched). Not valid for fewer than 2 points or a
/// degenerate cross-covariance (rank < m - 1 = 1, i.e. every singular value <= machine
/// epsilon, as evo checks).
AlignmentResult UmeyamaAlignment(const std::vector<Eigen::Vector2d>& est, const std::vector<Eigen::Vector2d>& gt);
AlignmentResult UmeyamaAlignment(const std::vector<SE2>& est, const std::vector<SE2>& gt);

/// T = Q_0 P_0^-1: the first estimated pose lands on the first true pose.
SE2 OriginAlignment(const SE2& gt_first, const SE2& est_first);

/// T * P for every pose (evo's PosePath3D.transform, left multiplication).
std::vector<SE2> TransformPoses(const SE2& T, const std::vector<SE2>& poses);

}  // namespace slambox
