#include "slam/ekf_slam_filter.hpp"

#include <Eigen/Cholesky>

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

EkfUpdateResult UpdateState(EkfSlamState& s, const std::vector<LinearizedObservation>& obs,
                            const Eigen::Matrix2d& R) {
  EkfUpdateResult result;
  if (obs.empty()) return result;
  const Eigen::Index k = 2 * static_cast<Eigen::Index>(obs.size());
  Eigen::VectorXd nu(k);
  for (size_t j = 0; j < obs.size(); ++j) nu.segment<2>(2 * j) = obs[j].innovation;

  const Eigen::MatrixXd C = LeftMultiplyH(obs, s.covariance);  // H P, k x n
  Eigen::MatrixXd S = RightMultiplyHt(obs, C);                  // H P H^T
  for (Eigen::Index j = 0; j < k; j += 2) S.block<2, 2>(j, j) += R;
  S = 0.5 * (S + S.transpose()).eval();
  const Eigen::LLT<Eigen::MatrixXd> llt(S);
  if (llt.info() != Eigen::Success) return result;
  const Eigen::MatrixXd K = llt.solve(C).transpose();  // P H^T S^-1, n x k

  result.applied = true;
  result.dof = static_cast<int>(k);
  result.nis = nu.dot(llt.solve(nu));
  s.mean.noalias() += K * nu;
  s.mean(2) = NormalizeAngle(s.mean(2));

  // Joseph form in two dense products: A = (I - K H) P = P - K C, then
  // P' = A - (A H^T) K^T + K R K^T = A + (K R - A H^T) K^T.
  Eigen::MatrixXd& P = s.covariance;
  P.noalias() -= K * C;
  Eigen::MatrixXd KR_minus_AHt = -RightMultiplyHt(obs, P);
  for (Eigen::Index j = 0; j < k; j += 2) KR_minus_AHt.middleCols<2>(j).noalias() += K.middleCols<2>(j) * R;
  P.noalias() += KR_minus_AHt * K.transpose();
  // Remove the round-off asymmetry: P = (P + P^T) / 2.
  for (Eigen::Index c = 0; c < P.cols(); ++c)
    for (Eigen::Index r = c + 1; r < P.rows(); ++r) P(r, c) = P(c, r) = 0.5 * (P(r, c) + P(c, r));
  return result;
}

}  // namespace slambox
