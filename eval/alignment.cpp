#include "eval/alignment.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <limits>

namespace slambox {

AlignmentResult UmeyamaAlignment(const std::vector<Eigen::Vector2d>& x, const std::vector<Eigen::Vector2d>& y) {
  AlignmentResult r;
  if (x.size() != y.size() || x.size() < 2) {
    r.reason = "Umeyama alignment needs at least 2 matched poses";
    return r;
  }
  const double n = static_cast<double>(x.size());
  Eigen::Vector2d mean_x = Eigen::Vector2d::Zero(), mean_y = Eigen::Vector2d::Zero();
  for (size_t i = 0; i < x.size(); ++i) {
    mean_x += x[i];
    mean_y += y[i];
  }
  mean_x /= n;
  mean_y /= n;
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();  // eq. 38
  for (size_t i = 0; i < x.size(); ++i) cov += (y[i] - mean_y) * (x[i] - mean_x).transpose();
  cov /= n;
  const Eigen::JacobiSVD<Eigen::Matrix2d> svd(cov, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector2d d = svd.singularValues();
  const int rank = (d.array() > std::numeric_limits<double>::epsilon()).count();
  if (rank < 1) {  // rank < m - 1 with m = 2
    r.reason = "degenerate covariance rank (all positions coincide): Umeyama alignment is not possible";
    return r;
  }
  const Eigen::Matrix2d& U = svd.matrixU();
  const Eigen::Matrix2d& V = svd.matrixV();
  Eigen::Matrix2d S = Eigen::Matrix2d::Identity();  // eq. 43: keep det(R) = +1
  if (U.determinant() * V.determinant() < 0.0) S(1, 1) = -1.0;
  const Eigen::Matrix2d R = U * S * V.transpose();  // eq. 40
  const Eigen::Vector2d t = mean_y - R * mean_x;    // eq. 41 with c = 1
  r.valid = true;
  r.T_gt_est = SE2(t.x(), t.y(), std::atan2(R(1, 0), R(0, 0)));
  return r;
}

AlignmentResult UmeyamaAlignment(const std::vector<SE2>& est, const std::vector<SE2>& gt) {
  std::vector<Eigen::Vector2d> x, y;
  x.reserve(est.size());
  y.reserve(gt.size());
  for (const auto& p : est) x.push_back(p.translation());
  for (const auto& p : gt) y.push_back(p.translation());
  return UmeyamaAlignment(x, y);
}

SE2 OriginAlignment(const SE2& gt_first, const SE2& est_first) { return gt_first * est_first.inverse(); }

std::vector<SE2> TransformPoses(const SE2& T, const std::vector<SE2>& poses) {
  std::vector<SE2> out;
  out.reserve(poses.size());
  for (const auto& p : poses) out.push_back(T * p);
  return out;
}

}  // namespace slambox
