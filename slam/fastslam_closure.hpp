#pragma once
// A FastSLAM particle's loop closure by re-observation (`closure_spread`). A particle that
// re-observes landmarks it last saw long ago (beyond the revisit search's widest window) with
// an innovation its pose prior cannot explain has drifted since then; the Kalman updates
// alone would move the pose only by what its short prior allows and pull the old landmarks
// toward the drifted pose, and the map it drew during the drift stays where the drift put
// it: lap 2 then repeats lap 1's bend (slam/README_fastslam.md, "Loop closure by
// re-observation"). EKF-SLAM's correlations move the whole map at such a closure.
//
// Here the particle relaxes its own path as a pose graph would, in closed form for dead
// reckoning's drift model: along the path since the old landmarks were seen, step k adds a
// heading error dtheta_k ~ N(0, v_k) that turns everything after it about the step's position
// p_k, and a position error dt_k ~ N(0, w_k I). The robot's pose error is then linear in them,
// dx = sum_k J_k (dtheta_k, dt_k) with J_k = [S(p_r - p_k) I; 1 0] (S(v) = (-v_y, v_x)), of
// prior covariance C = sum_k J_k diag(v_k, w_k, w_k) J_k^T. The correction dx is the pose that
// best explains the old observations under that prior (Gauss-Newton on
// sum |z - h(m, x)|^2_S + |x - x_prior|^2_C, S = H_m Sigma H_m^T + R), and the most likely
// errors given it are dtheta_k = v_k J_k^T lambda, dt_k = w_k lambda_xy with lambda = C^-1 dx
// (the minimum-norm solution under the prior). A landmark last seen at step j moves as the
// path did there: by the errors of the steps before j, a rotation by A_j = sum dtheta_k about
// the point B_j / A_j (B_j = sum dtheta_k p_k) and the shift sum dt_k.
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "core/se2.hpp"
#include "core/estimate.hpp"
#include "slam/fastslam_particle.hpp"
#include "slam/particle_path.hpp"


namespace slambox {

struct PoseProposal;  // slam/landmark_ekf.hpp

/// One step of the path since the old landmarks were seen: its position and the variances
/// dead reckoning added over it; `heading_rad2_until` the summed heading variance at its end
/// (a landmark's seen_heading_variance_rad2 finds its step).
struct DriftStep {
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();
  double heading_rad2 = 0, translation_m2 = 0, heading_rad2_until = 0;
};

/// The prior covariance C = sum_k J_k diag(v_k, w_k, w_k) J_k^T of the robot's pose error at
/// `robot_xy` (header).
Eigen::Matrix3d PathDriftCovariance(std::span<const DriftStep> steps, const Eigen::Vector2d& robot_xy);

/// The most likely step errors given the robot's correction dx (x, y, theta), as the motion
/// of a point last seen by the end of each step: a rotation by A about B / A and a shift D,
/// accumulated over the steps up to it.
struct PathCorrection {
  std::vector<double> until_rad2;  ///< per step: DriftStep::heading_rad2_until
  std::vector<double> A;           ///< [rad] per step: sum of dtheta_k up to it
  std::vector<Eigen::Vector2d> B, D;
  /// Where `m`, last seen when the heading variance was `seen_rad2`, moves (unchanged before
  /// the first step, by all of them after the last).
  Eigen::Vector2d Move(const Eigen::Vector2d& m, double seen_rad2) const;
  double Turn(double seen_rad2) const;  ///< [rad] the rotation it gets
};
PathCorrection RelaxPath(std::span<const DriftStep> steps, const Eigen::Vector2d& robot_xy, const Eigen::Vector3d& lambda);

/// The poses of `path` (oldest first, as PathPoses) moved as the lineage's relaxations moved its
/// map, oldest relaxation first: each pose up to a relaxation's time as a landmark last seen
/// then (PathCorrection::Move, its heading by Turn).
std::vector<PoseEstimate> RelaxedPath(const PathPtr& path, const PathRelaxation* relaxations,
                                      std::span<const DriftSample> drift);

/// The steps of the path ending at `newest` since dead reckoning's summed heading variance
/// was `since_rad2` (from `drift`), oldest first.
std::vector<DriftStep> PathSince(const PathNode* newest, double since_rad2, std::span<const DriftSample> drift);

/// Moves `p` to `corrected` (covariance turned with it) and each landmark last seen after
/// `since_rad2` (but those `stays` names) as its path did (RelaxPath of `steps` under the
/// robot's prior C). The closure's correction and the constellation's spread; recorded in
/// `p.relaxations` for the path. False (nothing moves) if C is not positive definite or the
/// correction dx is beyond the drift's gate, dx^T C^-1 dx > gate_chi2.
bool RelaxParticle(FastSlamParticle& p, const SE2& corrected, std::span<const DriftStep> steps, const Eigen::Matrix3d& C,
                   double gate_chi2, double since_rad2, const std::function<bool(int)>& stays);

/// Moves the particle's pose and each landmark `moves(key, landmark)` names rigidly by T
/// (covariances rotated).
void MoveParticle(FastSlamParticle& p, const SE2& T, const std::function<bool(int, const LandmarkGaussian&)>& moves);

/// The Gauss-Newton pose of the closure: argmin over x of sum_j |z_j - h(m_j, x)|^2_{S_j} +
/// |x - prior.mean|^2_{prior.covariance}, S_j = H_m Sigma_j H_m^T + R (x added as a vector,
/// the heading wrapped). `observed` pairs a landmark with its (range, bearing).
SE2 ClosurePose(const PoseProposal& prior, std::span<const std::pair<const LandmarkGaussian*, Eigen::Vector2d>> observed,
                const Eigen::Matrix2d& R);

/// Corrects `p` for a closure on the scan's observations `z` (range, bearing) associated to
/// landmark `keys` (negative: none) before the scan's update, with the options' travel, heading
/// variance, drift, R and closure fields (ParticleUpdateOptions; the loop closes over one
/// range_max of travel after old landmarks return): if the old ones' joint innovation at the
/// particle's prior exceeds the chi-square gate and the drift-prior pose explains them within
/// it, the pose moves to that pose and each landmark last seen since the stretch began as its
/// path did (above). Returns the pose correction T = x' x^-1, or none.
std::optional<SE2> CorrectClosure(FastSlamParticle& p, std::span<const int> keys, std::span<const Eigen::Vector2d> z,
                                  const ParticleUpdateOptions& options);

}  // namespace slambox
