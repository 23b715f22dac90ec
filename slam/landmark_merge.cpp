#include "slam/landmark_merge.hpp"

#include <Eigen/Cholesky>
#include <limits>

namespace slambox {

namespace {
/// H P for H = [.. I (at a) .. -I (at b) ..]: rows of a minus rows of b, 2 x n.
Eigen::MatrixXd DifferenceRows(const Eigen::MatrixXd& P, int a, int b) {
  return P.middleRows<2>(3 + 2 * a) - P.middleRows<2>(3 + 2 * b);
}
}  // namespace

double LandmarkDifferenceChi2(const EkfSlamState& s, int a, int b) {
  const Eigen::Index ia = 3 + 2 * a, ib = 3 + 2 * b;
  const Eigen::Matrix2d C = s.covariance.block<2, 2>(ia, ia) + s.covariance.block<2, 2>(ib, ib) -
                            s.covariance.block<2, 2>(ia, ib) - s.covariance.block<2, 2>(ib, ia);
  const Eigen::LLT<Eigen::Matrix2d> llt(0.5 * (C + C.transpose()));
  if (llt.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
  const Eigen::Vector2d D = s.Landmark(a) - s.Landmark(b);
  return D.dot(llt.solve(D));
}

bool MergeLandmarks(EkfSlamState& s, int keep, int remove) {
  const Eigen::MatrixXd HP = DifferenceRows(s.covariance, keep, remove);  // 2 x n
  const Eigen::Matrix2d C = HP.middleCols<2>(3 + 2 * keep) - HP.middleCols<2>(3 + 2 * remove);
  const Eigen::LLT<Eigen::Matrix2d> llt(0.5 * (C + C.transpose()));
  if (llt.info() != Eigen::Success) return false;
  const Eigen::Vector2d D = s.Landmark(keep) - s.Landmark(remove);
  const Eigen::MatrixXd K = llt.solve(HP).transpose();  // P H^T C^-1, n x 2
  s.mean.noalias() -= K * D;
  s.mean(2) = NormalizeAngle(s.mean(2));
  s.covariance.noalias() -= K * HP;
  s.covariance = 0.5 * (s.covariance + s.covariance.transpose()).eval();
  RemoveLandmark(s, remove);
  return true;
}

}  // namespace slambox
