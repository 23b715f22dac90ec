#include "slam/landmark_merge.hpp"

#include <Eigen/Cholesky>
#include <limits>

namespace slambox {

PointDifference DifferenceOf(const Eigen::VectorXd& x, const Eigen::MatrixXd& P, Eigen::Index ia, Eigen::Index ib) {
  PointDifference d;
  d.C = P.block<2, 2>(ia, ia) + P.block<2, 2>(ib, ib) - P.block<2, 2>(ia, ib) - P.block<2, 2>(ib, ia);
  d.C = 0.5 * (d.C + d.C.transpose());
  d.D = x.segment<2>(ia) - x.segment<2>(ib);
  const Eigen::LLT<Eigen::Matrix2d> llt(d.C);
  d.d2 = llt.info() == Eigen::Success ? d.D.dot(llt.solve(d.D)) : std::numeric_limits<double>::infinity();
  return d;
}

bool ConditionOnEqual(Eigen::VectorXd& x, Eigen::MatrixXd& P, Eigen::Index ia, Eigen::Index ib) {
  const Eigen::MatrixXd HP = P.middleRows<2>(ia) - P.middleRows<2>(ib);  // H P, 2 x n
  const Eigen::Matrix2d C = HP.middleCols<2>(ia) - HP.middleCols<2>(ib);
  const Eigen::LLT<Eigen::Matrix2d> llt(0.5 * (C + C.transpose()));
  if (llt.info() != Eigen::Success) return false;
  const Eigen::Vector2d D = x.segment<2>(ia) - x.segment<2>(ib);
  const Eigen::MatrixXd K = llt.solve(HP).transpose();  // P H^T C^-1, n x 2
  x.noalias() -= K * D;
  P.noalias() -= K * HP;
  P = 0.5 * (P + P.transpose()).eval();
  return true;
}

double LandmarkDifferenceChi2(const EkfSlamState& s, int a, int b) {
  return DifferenceOf(s.mean, s.covariance, 3 + 2 * a, 3 + 2 * b).d2;
}

bool MergeLandmarks(EkfSlamState& s, int keep, int remove) {
  if (!ConditionOnEqual(s.mean, s.covariance, 3 + 2 * keep, 3 + 2 * remove)) return false;
  s.mean(2) = NormalizeAngle(s.mean(2));
  RemoveLandmark(s, remove);
  return true;
}

}  // namespace slambox
