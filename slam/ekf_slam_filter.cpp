#include "slam/ekf_slam_filter.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "slam/range_bearing.hpp"

namespace slambox {

EkfSlamState MakeInitialState(const SE2& start) {
  EkfSlamState s;
  s.mean = start.vector();
  s.covariance = Eigen::MatrixXd::Zero(3, 3);
  return s;
}

void PredictState(EkfSlamState& s, const SE2& predicted_pose, const Eigen::Matrix3d& J,
                  const Eigen::Matrix3d& Q_pose) {
  const Eigen::Index map_dim = s.mean.size() - 3;
  s.mean.head<3>() = predicted_pose.vector();
  const Eigen::Matrix3d P_rr = s.covariance.topLeftCorner<3, 3>();
  const Eigen::Matrix3d P_rr_new = J * P_rr * J.transpose() + Q_pose;
  s.covariance.topLeftCorner<3, 3>() = 0.5 * (P_rr_new + P_rr_new.transpose());
  if (map_dim > 0) {  // the 3 x 2n robot-map rows, O(n)
    const Eigen::MatrixXd P_rm = J * s.covariance.topRightCorner(3, map_dim);
    s.covariance.topRightCorner(3, map_dim) = P_rm;
    s.covariance.bottomLeftCorner(map_dim, 3) = P_rm.transpose();
  }
}

int AddLandmark(EkfSlamState& s, const Eigen::Vector2d& z, const Eigen::Matrix2d& R) {
  const Eigen::Index n = s.mean.size();
  const LandmarkInitialization init = InverseObservation(s.Pose(), z);
  s.mean.conservativeResize(n + 2);
  s.mean.tail<2>() = init.landmark;
  s.covariance.conservativeResize(n + 2, n + 2);
  const Eigen::MatrixXd P_m_all = init.J_landmark_pose * s.covariance.topLeftCorner(3, n);  // 2 x n
  s.covariance.bottomLeftCorner(2, n) = P_m_all;
  s.covariance.topRightCorner(n, 2) = P_m_all.transpose();
  const Eigen::Matrix2d P_mm =
      init.J_landmark_pose * s.covariance.topLeftCorner<3, 3>() * init.J_landmark_pose.transpose() +
      init.J_landmark_z * R * init.J_landmark_z.transpose();
  s.covariance.bottomRightCorner<2, 2>() = 0.5 * (P_mm + P_mm.transpose());
  return s.NumLandmarks() - 1;
}

void RemoveLandmark(EkfSlamState& s, int index) {
  const Eigen::Index n = s.mean.size(), a = 3 + 2 * index, tail = n - a - 2;
  assert(index >= 0 && a + 2 <= n);
  if (tail > 0) {
    s.mean.segment(a, tail) = s.mean.tail(tail).eval();
    s.covariance.middleRows(a, tail) = s.covariance.bottomRows(tail).eval();
    s.covariance.middleCols(a, tail) = s.covariance.rightCols(tail).eval();
  }
  s.mean.conservativeResize(n - 2);
  s.covariance.conservativeResize(n - 2, n - 2);
}

namespace {
/// Y = H X for X with n rows (sparse H): rows 2j..2j+1 = Jr X_r + Jm X_m.
Eigen::MatrixXd LeftMultiplyH(const std::vector<LinearizedObservation>& obs, const Eigen::MatrixXd& X) {
  Eigen::MatrixXd Y(2 * obs.size(), X.cols());
  for (size_t j = 0; j < obs.size(); ++j)
    Y.middleRows<2>(2 * j).noalias() =
        obs[j].J_z_pose * X.topRows<3>() + obs[j].J_z_landmark * X.middleRows<2>(3 + 2 * obs[j].landmark);
  return Y;
}
/// Y = X H^T for X with n columns.
Eigen::MatrixXd RightMultiplyHt(const std::vector<LinearizedObservation>& obs, const Eigen::MatrixXd& X) {
  Eigen::MatrixXd Y(X.rows(), 2 * obs.size());
  for (size_t j = 0; j < obs.size(); ++j)
    Y.middleCols<2>(2 * j).noalias() = X.leftCols<3>() * obs[j].J_z_pose.transpose() +
                                       X.middleCols<2>(3 + 2 * obs[j].landmark) * obs[j].J_z_landmark.transpose();
  return Y;
}
}  // namespace

namespace {
/// The batch's gain at one linearization: C = H P, S = H P H^T + R (its Cholesky), K = P H^T S^-1.
struct BatchGain {
  Eigen::MatrixXd C, S, K;
  Eigen::LLT<Eigen::MatrixXd> llt;
};

bool ComputeGain(const EkfSlamState& s, const std::vector<LinearizedObservation>& obs, const Eigen::Matrix2d& R,
                 BatchGain& g) {
  const Eigen::Index k = 2 * static_cast<Eigen::Index>(obs.size());
  g.C = LeftMultiplyH(obs, s.covariance);  // H P, k x n
  g.S = RightMultiplyHt(obs, g.C);          // H P H^T
  for (Eigen::Index j = 0; j < k; j += 2) g.S.block<2, 2>(j, j) += R;
  g.S = 0.5 * (g.S + g.S.transpose()).eval();
  g.llt.compute(g.S);
  if (g.llt.info() != Eigen::Success) return false;
  g.K = g.llt.solve(g.C).transpose();  // P H^T S^-1, n x k
  return true;
}

Eigen::VectorXd StackedInnovations(const std::vector<LinearizedObservation>& obs) {
  Eigen::VectorXd nu(2 * static_cast<Eigen::Index>(obs.size()));
  for (size_t j = 0; j < obs.size(); ++j) nu.segment<2>(2 * j) = obs[j].innovation;
  return nu;
}

// Joseph form P' = (I - K H) P (I - K H)^T + K R K^T, expanded (exact for any gain K):
// P' = P - K C - C^T K^T + K S K^T = P + K E + E^T K^T with E = S K^T / 2 - C.
// Only the lower triangle is computed (two triangular products, n^2 k flops each),
// then mirrored: P' is exactly symmetric.
void JosephUpdate(Eigen::MatrixXd& P, const BatchGain& g) {
  const Eigen::MatrixXd E = 0.5 * g.S * g.K.transpose() - g.C;  // k x n
  P.triangularView<Eigen::Lower>() += g.K * E;
  P.triangularView<Eigen::Lower>() += E.transpose() * g.K.transpose();
  P.triangularView<Eigen::StrictlyUpper>() = P.transpose();
}
}  // namespace

EkfUpdateResult UpdateState(EkfSlamState& s, const std::vector<LinearizedObservation>& obs,
                            const Eigen::Matrix2d& R) {
  EkfUpdateResult result;
  if (obs.empty()) return result;
  BatchGain g;
  if (!ComputeGain(s, obs, R, g)) return result;
  const Eigen::VectorXd nu = StackedInnovations(obs);
  result.applied = true;
  result.dof = static_cast<int>(nu.size());
  result.nis = nu.dot(g.llt.solve(nu));
  s.mean.noalias() += g.K * nu;
  s.mean(2) = NormalizeAngle(s.mean(2));
  JosephUpdate(s.covariance, g);
  return result;
}

namespace {
/// After the additive update from `prior`: the exact retraction of its correction and the
/// covariance carried to the new estimate (InvariantUpdateState, slam/ekf_slam_filter.hpp).
void RetractInvariant(EkfSlamState& s, const Eigen::VectorXd& prior) {
  const double phi = NormalizeAngle(s.mean(2) - prior(2));  // xi_theta (= the heading's correction)
  // exp on SE_{1+n}(2): R(phi) and V(phi) = (sin phi / phi) I + ((1 - cos phi) / phi) J.
  const double a = std::abs(phi) < 1e-6 ? 1.0 - phi * phi / 6.0 : std::sin(phi) / phi;
  const double b = std::abs(phi) < 1e-6 ? 0.5 * phi : (1.0 - std::cos(phi)) / phi;
  Eigen::Matrix2d rotation, V, J;
  rotation << std::cos(phi), -std::sin(phi), std::sin(phi), std::cos(phi);
  V << a, -b, b, a;
  J << 0.0, -1.0, 1.0, 0.0;
  const Eigen::Index n = s.mean.size();
  Eigen::VectorXd dc = Eigen::VectorXd::Zero(n);  // c(x̂') - c(x̂)
  for (Eigen::Index k = 0; k < n; k += (k == 0 ? 3 : 2)) {  // the robot's position, then each landmark's
    const Eigen::Vector2d q = prior.segment<2>(k);
    const Eigen::Vector2d xi = s.mean.segment<2>(k) - q - phi * (J * q);  // T(x̂)^-1 K nu on q's rows
    const Eigen::Vector2d moved = rotation * q + V * xi;
    s.mean.segment<2>(k) = moved;
    dc.segment<2>(k) = J * (moved - q);
  }
  // A P A^T = P + dc r^T + r dc^T + P_tt dc dc^T (r = P e_theta) = P + dc w^T + w dc^T with
  // w = r + P_tt dc / 2: a rank-2 update of the lower triangle, mirrored (exactly symmetric,
  // no n x n temporary).
  const Eigen::VectorXd w = s.covariance.col(2) + 0.5 * s.covariance(2, 2) * dc;
  s.covariance.selfadjointView<Eigen::Lower>().rankUpdate(dc, w);
  s.covariance.triangularView<Eigen::StrictlyUpper>() = s.covariance.transpose();
}
}  // namespace

EkfUpdateResult InvariantUpdateState(EkfSlamState& s, const std::vector<LinearizedObservation>& obs,
                                     const Eigen::Matrix2d& R) {
  const Eigen::VectorXd prior = s.mean;
  const EkfUpdateResult result = UpdateState(s, obs, R);
  if (result.applied) RetractInvariant(s, prior);
  return result;
}

EkfUpdateResult IteratedUpdateState(EkfSlamState& s, const std::vector<LandmarkMeasurement>& m,
                                    const Eigen::Matrix2d& R, int iterations, double step_gate_chi2) {
  EkfUpdateResult result;
  if (m.empty()) return result;
  const Eigen::VectorXd prior = s.mean;
  Eigen::VectorXd x = prior;  // the iterate x_i
  std::vector<LinearizedObservation> lin(m.size());
  // The last iterate's gain and the next one's, alternating: never copied or swapped (a
  // default-constructed Eigen::LLT holds an uninitialized ComputationInfo that a copy reads).
  BatchGain gains[2];
  int last = -1;
  const Eigen::Matrix3d P_rr = s.covariance.topLeftCorner<3, 3>();  // the prior's robot block
  for (int i = 0; i < std::max(1, iterations); ++i) {
    const SE2 pose{x(0), x(1), x(2)};
    // d = x̂ - x_i on the robot and on each measured landmark (heading wrapped).
    Eigen::Vector3d d_pose = prior.head<3>() - x.head<3>();
    d_pose(2) = NormalizeAngle(d_pose(2));
    for (size_t j = 0; j < m.size(); ++j) {
      const Eigen::Index a = 3 + 2 * m[j].landmark;
      const ObservationPrediction p = PredictObservation(pose, x.segment<2>(a));
      lin[j] = {m[j].landmark, Innovation(m[j].z, p.z), p.J_z_pose, p.J_z_landmark};
      if (i > 0) lin[j].innovation -= p.J_z_pose * d_pose + p.J_z_landmark * (prior.segment<2>(a) - x.segment<2>(a));
    }
    const int next_gain = last == 0 ? 1 : 0;
    if (!ComputeGain(s, lin, R, gains[next_gain])) {
      if (i == 0) return result;  // not positive definite at the prior: nothing applied
      break;                      // keep the last iterate and its gain
    }
    last = next_gain;
    const BatchGain& g = gains[last];
    const Eigen::VectorXd nu = StackedInnovations(lin);
    if (i == 0) result.nis = nu.dot(g.llt.solve(nu));
    Eigen::VectorXd next = prior;
    next.noalias() += g.K * nu;
    next(2) = NormalizeAngle(next(2));
    Eigen::VectorXd step = next - x;
    step(2) = NormalizeAngle(step(2));
    x = next;
    result.iterations = i + 1;
    if (step.lpNorm<Eigen::Infinity>() < 1e-9) break;
    if (i == 0 && step_gate_chi2 > 0.0) {  // the EKF step: is it small enough to trust h's tangent?
      const Eigen::Vector3d d = step.head<3>();
      if (d.dot(P_rr.ldlt().solve(d)) < step_gate_chi2) break;
    }
  }
  result.applied = true;
  result.dof = 2 * static_cast<int>(m.size());
  s.mean = x;
  JosephUpdate(s.covariance, gains[last]);
  return result;
}

}  // namespace slambox
