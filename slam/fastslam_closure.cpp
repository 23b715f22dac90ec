#include "slam/fastslam_closure.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <limits>
#include <vector>

#include "core/chi_square.hpp"
#include "slam/landmark_ekf.hpp"
#include "slam/particle_path.hpp"
#include "slam/range_bearing.hpp"

namespace slambox {

namespace {

/// sum_j nu_j^T S_j^-1 nu_j at pose x, S_j = H_m Sigma_j H_m^T + R (+ H_x P H_x^T for a prior P).
double JointInnovation(const PoseProposal& at, std::span<const std::pair<const LandmarkGaussian*, Eigen::Vector2d>> observed,
                       const Eigen::Matrix2d& R) {
  double d2 = 0.0;
  for (const auto& [lm, z] : observed) {
    const PredictedMeasurement predicted = PredictMeasurement(at, *lm, R);
    const Eigen::Vector2d nu = Innovation(z, predicted.z_hat);
    d2 += nu.dot(predicted.L_inverse * nu);
  }
  return d2;
}

// d(robot pose) / d(dtheta_k): a heading error at step k turns the robot about the step.
Eigen::Vector3d StepJacobian(const Eigen::Vector2d& robot_xy, const Eigen::Vector2d& step_xy) {
  return {-(robot_xy.y() - step_xy.y()), robot_xy.x() - step_xy.x(), 1.0};
}

// Turns a pose covariance's position block with the heading by `angle_rad`: A P A^T with
// A = diag(R(angle), 1).
void TurnPoseCovariance(Eigen::Matrix3d& P, double angle_rad) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  A.topLeftCorner<2, 2>() = RotationMatrix(angle_rad);
  P = A * P * A.transpose();
}

// True when C is symmetric positive definite (a drift prior the relaxation can invert).
bool PositiveDefinite(const Eigen::Matrix3d& C) {
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(C);
  return ldlt.info() == Eigen::Success && ldlt.vectorD().minCoeff() > 0.0;
}

// The number of samples at or before t_s.
size_t SamplesUntil(std::span<const DriftSample> drift, double t_s) {
  return std::upper_bound(drift.begin(), drift.end(), t_s, [](double t, const DriftSample& d) { return t < d.t_s; }) -
         drift.begin();
}

}  // namespace

Eigen::Matrix3d PathDriftCovariance(std::span<const DriftStep> steps, const Eigen::Vector2d& robot_xy) {
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  for (const DriftStep& k : steps) {
    const Eigen::Vector3d J = StepJacobian(robot_xy, k.xy);
    C += k.heading_rad2 * J * J.transpose();
    C.topLeftCorner<2, 2>() += k.translation_m2 * Eigen::Matrix2d::Identity();
  }
  return C;
}

PathCorrection RelaxPath(std::span<const DriftStep> steps, const Eigen::Vector2d& robot_xy, const Eigen::Vector3d& lambda) {
  PathCorrection c;
  double A = 0.0;
  Eigen::Vector2d B = Eigen::Vector2d::Zero(), D = Eigen::Vector2d::Zero();
  for (const DriftStep& k : steps) {
    const double dtheta = k.heading_rad2 * StepJacobian(robot_xy, k.xy).dot(lambda);
    A += dtheta;
    B += dtheta * k.xy;
    D += k.translation_m2 * lambda.head<2>();
    c.until_rad2.push_back(k.heading_rad2_until);
    c.A.push_back(A);
    c.B.push_back(B);
    c.D.push_back(D);
  }
  return c;
}

namespace {
// The index of the last step ending by `seen_rad2`, or -1.
int StepOf(const PathCorrection& c, double seen_rad2) {
  return static_cast<int>(std::upper_bound(c.until_rad2.begin(), c.until_rad2.end(), seen_rad2) - c.until_rad2.begin()) - 1;
}
}  // namespace

Eigen::Vector2d PathCorrection::Move(const Eigen::Vector2d& m, double seen_rad2) const {
  const int j = StepOf(*this, seen_rad2);
  if (j < 0) return m;
  // m + (R(A) - I)(m - B / A) + D, written so that it stays exact as A -> 0: (R(A) - I) / A -> S.
  const double a = A[j];
  const Eigen::Vector2d v = a * m - B[j];  // A m - B
  const double s = std::abs(a) > 1e-12 ? std::sin(a) / a : 1.0;
  const double k = std::abs(a) > 1e-12 ? (std::cos(a) - 1.0) / a : 0.0;
  return m + Eigen::Vector2d(k * v.x() - s * v.y(), s * v.x() + k * v.y()) + D[j];
}

double PathCorrection::Turn(double seen_rad2) const {
  const int j = StepOf(*this, seen_rad2);
  return j < 0 ? 0.0 : A[j];
}

SE2 ClosurePose(const PoseProposal& prior, std::span<const std::pair<const LandmarkGaussian*, Eigen::Vector2d>> observed,
                const Eigen::Matrix2d& R) {
  const Eigen::Matrix3d prior_information = prior.covariance.inverse();
  Eigen::Vector3d delta = Eigen::Vector3d::Zero();  // x = prior.mean + delta
  for (int iteration = 0; iteration < 20; ++iteration) {
    const SE2 x = SE2::FromVector(prior.mean.vector() + delta);
    // Normal equations of the linearization at x: (sum J^T S^-1 J + P0^-1) step = sum J^T S^-1 nu - P0^-1 delta.
    Eigen::Matrix3d A = prior_information;
    Eigen::Vector3d b = -prior_information * delta;
    for (const auto& [lm, z] : observed) {
      const ObservationPrediction h = PredictObservation(x, lm->mean);
      const Eigen::Matrix2d S = h.J_z_landmark * lm->covariance * h.J_z_landmark.transpose() + R;
      const Eigen::Matrix<double, 3, 2> JtSi = h.J_z_pose.transpose() * S.inverse();
      A += JtSi * h.J_z_pose;
      b += JtSi * Innovation(z, h.z);
    }
    const Eigen::Vector3d step = A.ldlt().solve(b);
    delta += step;
    if (step.head<2>().norm() < 1e-9 && std::abs(step.z()) < 1e-12) break;
  }
  return SE2::FromVector(prior.mean.vector() + delta);
}

void MoveParticle(FastSlamParticle& p, const SE2& T, const std::function<bool(int, const LandmarkGaussian&)>& moves) {
  p.pose = T * p.pose;
  TurnPoseCovariance(p.pose_covariance, T.theta);
  std::vector<std::pair<int, LandmarkGaussian>> moved;
  ForEachLandmark(p.map, [&](int key, const LandmarkGaussian& lm) {
    if (!moves(key, lm)) return;
    LandmarkGaussian m = lm;
    m.mean = T * lm.mean;
    m.covariance = T.rotation() * lm.covariance * T.rotation().transpose();
    moved.emplace_back(key, m);
  });
  for (const auto& [key, lm] : moved) SetLandmark(p.map, key, lm);
}

std::vector<DriftStep> PathSince(const PathNode* newest, double since_rad2, std::span<const DriftSample> drift) {
  const auto drift_at = [&](double t_s) {  // the last sample at or before t_s
    const size_t n = SamplesUntil(drift, t_s);
    return n == 0 ? DriftSample{} : drift[n - 1];
  };
  std::vector<DriftStep> steps;
  DriftSample after = drift.empty() ? DriftSample{} : drift.back();
  for (const PathNode* node = newest; node != nullptr && after.heading_rad2 > since_rad2; node = node->parent.get()) {
    const DriftSample at = drift_at(node->t_s);
    steps.push_back({node->pose.translation(), after.heading_rad2 - at.heading_rad2,
                     after.translation_m2 - at.translation_m2, after.heading_rad2});
    after = at;
  }
  std::reverse(steps.begin(), steps.end());
  return steps;
}

bool RelaxParticle(FastSlamParticle& p, const SE2& corrected, std::span<const DriftStep> steps, const Eigen::Matrix3d& C,
                   double gate_chi2, double since_rad2, const std::function<bool(int)>& stays) {
  if (!PositiveDefinite(C)) return false;
  const Eigen::Vector3d dx(corrected.x - p.pose.x, corrected.y - p.pose.y, NormalizeAngle(corrected.theta - p.pose.theta));
  const Eigen::Vector3d lambda = C.ldlt().solve(dx);
  // A correction the drift model makes unlikely would be spread as large turns of opposite
  // signs along the path that cancel at the robot: a false match, or drift of another kind.
  if (dx.dot(lambda) > gate_chi2) return false;
  const PathCorrection path = RelaxPath(steps, p.pose.translation(), lambda);
  const double t_s = p.path ? p.path->t_s : 0.0;
  p.relaxations = std::make_shared<const PathRelaxation>(
      PathRelaxation{t_s, since_rad2, lambda, p.pose.translation(), p.relaxations});
  std::vector<std::pair<int, LandmarkGaussian>> moved;
  ForEachLandmark(p.map, [&](int key, const LandmarkGaussian& lm) {
    if (lm.seen_heading_variance_rad2 <= since_rad2 || stays(key)) return;
    LandmarkGaussian m = lm;
    m.mean = path.Move(lm.mean, lm.seen_heading_variance_rad2);
    const Eigen::Matrix2d R = RotationMatrix(path.Turn(lm.seen_heading_variance_rad2));
    m.covariance = R * lm.covariance * R.transpose();
    moved.emplace_back(key, m);
  });
  for (const auto& [key, lm] : moved) SetLandmark(p.map, key, lm);
  TurnPoseCovariance(p.pose_covariance, dx.z());
  p.pose = corrected;
  return true;
}

std::vector<PoseEstimate> RelaxedPath(const PathPtr& path, const PathRelaxation* relaxations,
                                      std::span<const DriftSample> drift) {
  std::vector<PoseEstimate> out;
  for (const PathNode* n : PathPoses(path)) out.push_back({n->t_s, n->pose, Eigen::Matrix3d::Zero(), false});
  std::vector<const PathRelaxation*> oldest_first;
  for (const PathRelaxation* r = relaxations; r != nullptr; r = r->parent.get()) oldest_first.push_back(r);
  std::reverse(oldest_first.begin(), oldest_first.end());
  const auto heading_rad2_at = [&](double t_s) {
    const size_t n = SamplesUntil(drift, t_s);
    return n == 0 ? 0.0 : drift[n - 1].heading_rad2;
  };
  for (const PathRelaxation* r : oldest_first) {
    const PathNode* at = path.get();  // the path as it was at the relaxation
    while (at != nullptr && at->t_s > r->t_s) at = at->parent.get();
    const std::vector<DriftStep> steps = PathSince(at, r->since_rad2, drift.first(SamplesUntil(drift, r->t_s)));
    const PathCorrection correction = RelaxPath(steps, r->robot_xy, r->lambda);
    for (PoseEstimate& e : out) {
      if (e.t_s > r->t_s) break;
      const double v = heading_rad2_at(e.t_s);
      if (v <= r->since_rad2) continue;
      const Eigen::Vector2d xy = correction.Move(e.pose.translation(), v);
      e.pose = SE2(xy.x(), xy.y(), e.pose.theta + correction.Turn(v));
    }
  }
  return out;
}

std::optional<SE2> CorrectClosure(FastSlamParticle& p, std::span<const int> keys, std::span<const Eigen::Vector2d> z,
                                  const ParticleUpdateOptions& s) {
  std::vector<std::pair<const LandmarkGaussian*, Eigen::Vector2d>> old;
  double paired_rad2 = 0.0;  // the latest of the old sightings
  for (size_t j = 0; j < keys.size(); ++j) {
    const LandmarkGaussian* lm = keys[j] >= 0 ? FindLandmark(p.map, keys[j]) : nullptr;
    if (lm == nullptr || s.travel_m - lm->seen_travel_m <= s.closure_old_after_m) continue;
    old.emplace_back(lm, z[j]);
    paired_rad2 = std::max(paired_rad2, lm->seen_heading_variance_rad2);
  }
  if (old.empty()) return std::nullopt;
  // A loop closes when old landmarks return after a stretch without any, over the next
  // range_max of travel (one landmark fixes two of the drift's three dof; the place's other
  // landmarks come into view): afterwards the path re-observes the closed loop's map, which
  // the correction has already moved.
  if (s.travel_m - p.old_seen_travel_m > s.closure_old_after_m) {
    p.closure_travel_m = s.travel_m;
    p.closure_since_rad2 = p.old_seen_heading_rad2;
  }
  p.old_seen_travel_m = s.travel_m;
  p.old_seen_heading_rad2 = s.heading_variance_rad2;
  if (p.closure_travel_m < 0.0 || s.travel_m - p.closure_travel_m > s.range_max_m) return std::nullopt;
  // The drift to spread is the stretch's: before it the path re-observed the old map (a loop
  // closed in between), or it is where the old landmarks were seen, whichever is later.
  const double since_rad2 = std::max(paired_rad2, p.closure_since_rad2);
  const double gate = ChiSquareQuantile(s.closure_gate_prob, 2.0 * static_cast<double>(old.size()));
  // A closure only where the particle's own prior cannot explain the old landmarks.
  if (JointInnovation({p.pose, p.pose_covariance}, old, s.R) <= gate) return std::nullopt;
  const std::vector<DriftStep> steps = PathSince(p.path.get(), since_rad2, s.drift);
  const Eigen::Matrix3d C = p.pose_covariance + PathDriftCovariance(steps, p.pose.translation());
  if (!PositiveDefinite(C)) return std::nullopt;  // no drift since (dead reckoning without noise)
  const SE2 corrected = ClosurePose({p.pose, C}, old, s.R);
  // ... and only where the drift explains them (else the association, not the pose, is wrong).
  if (JointInnovation({corrected, Eigen::Matrix3d::Zero()}, old, s.R) > gate) return std::nullopt;
  const SE2 T = corrected * p.pose.inverse();
  if (!RelaxParticle(p, corrected, steps, C, s.drift_gate_chi2, since_rad2, [](int) { return false; })) return std::nullopt;
  return T;
}

}  // namespace slambox
