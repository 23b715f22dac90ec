#pragma once
// The landmark SLAM graph of Thrun's GraphSLAM (Prob. Robotics, Ch. 11) solved as
// nonlinear least squares with Ceres: keyframe poses and landmark positions are
// parameter blocks; odometry between-factors link consecutive keyframes, range-bearing
// factors link a keyframe to a landmark; keyframe 0 is held constant (gauge).
//   odometry:      the pose graph's between-poses factor (slam/pose_graph_cost.hpp),
//                  e = [R_i^T (t_j - t_i) - t_ij ; wrap(theta_j - theta_i - theta_ij)], info Sigma_ij^-1
//   range-bearing: e = [r - |m - t_i| ; wrap(b - atan2(m - t_i) + theta_i)], info R^-1
// Poses are SE2, solved on the pose manifold of slam/angle_manifold.hpp (as the pose graph).
// Marginal covariances of every pose and landmark: selected inversion of the information
// matrix (slam/sparse_marginals.hpp; deterministic, no ceres::Covariance).
// An observation whose landmark the solution puts within the range's standard deviation of
// its keyframe (the range-bearing factor's singularity) is left out and the graph solved
// again (LandmarkGraphSolution::observations_left_out; slam/landmark_graph.cpp says why).
#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

#include "core/se2.hpp"

namespace slambox {

struct OdometryConstraint {
  int from = 0;  ///< keyframe index; `to` is from + 1
  SE2 T_from_to;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();  ///< over (dx [m], dy [m], dtheta [rad])
};

/// The covariance an odometry factor is weighed with: the constraint's, floored (1e-8 on the
/// diagonal) so that a standing-still segment stays invertible.
Eigen::Matrix3d FactorCovariance(const OdometryConstraint& odometry);

struct RangeBearingConstraint {
  int keyframe = 0;
  int landmark = 0;  ///< key into LandmarkGraph::landmarks
  Eigen::Vector2d z = Eigen::Vector2d::Zero();  ///< (range [m], bearing [rad])
};

struct LandmarkGraph {
  std::vector<SE2> poses;                    ///< each keyframe's pose: guess in, solution out
  std::map<int, Eigen::Vector2d> landmarks;  ///< key -> position [m]: guess in, solution out
  std::vector<OdometryConstraint> odometry;
  std::vector<RangeBearingConstraint> observations;  ///< naming a missing landmark: skipped
  Eigen::Matrix2d observation_covariance = Eigen::Matrix2d::Identity();  ///< R [m^2, rad^2]
};

struct LandmarkGraphOptions {
  /// Levenberg-Marquardt iterations before Ceres gives up. Generous: after a long loop with
  /// tens of degrees of heading drift LM needs ~300 (held-out parks lm3_10, lm4_8), and a
  /// graph that converges sooner stops there (slam/README_landmark_slam.md).
  int max_iterations = 1000;
  bool compute_covariance = true;  ///< every pose's and landmark's marginal covariance
  double huber_scale = 0.0;  ///< Huber loss on whitened range-bearing residuals (0 = none)
  bool joint_landmark_covariance = false;  ///< the joint covariance of all landmarks (independent of compute_covariance)
  /// Ceres stops when an iteration lowers the cost by less than this fraction (Ceres' own
  /// default): two solutions whose chi2 differ by less are the same to the solver.
  double function_tolerance = 1e-6;
  /// Landmarks held at their guesses: only the poses are solved (no marginals).
  bool hold_landmarks = false;
};

struct LandmarkGraphSolution {
  std::string termination;  ///< Ceres' termination type
  bool usable = false;
  int iterations = 0;
  double chi2_initial = 0.0;  ///< 2 x Ceres' cost (sum of squared whitened residuals)
  double chi2_final = 0.0;
  int num_residuals = 0;
  bool covariance_ok = false;
  std::vector<Eigen::Matrix3d> pose_covariances;      ///< keyframe 0: zero (held constant)
  std::map<int, Eigen::Matrix2d> landmark_covariances;
  /// joint_landmark_covariance: all landmarks' positions stacked in key order (2 rows each)
  Eigen::MatrixXd landmark_joint_covariance;
  /// Observations left out because the solution put their landmark closer to their keyframe
  /// than the range's standard deviation, where the range-bearing factor is singular (the
  /// graph is solved again without them; SolveLandmarkGraph's comment).
  int observations_left_out = 0;
};

LandmarkGraphSolution SolveLandmarkGraph(LandmarkGraph& graph, const LandmarkGraphOptions& options);

}  // namespace slambox
