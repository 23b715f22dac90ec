#pragma once
// Landmark map accuracy. Estimated landmarks are first moved by the trajectory alignment
// T_gt_est, then matched to the true ones by id (known data association) or, without
// ids, by the optimal assignment minimizing sum min(d, c)^p (the OSPA assignment).
// OSPA (Schuhmacher, Vo, Vo 2008, eq. 3), for |X| = m <= n = |Y|:
//   d_p^c(X, Y) = ( (min_pi sum_i min(c, |x_i - y_pi(i)|)^p + c^p (n - m)) / n )^(1/p),
// 0 for two empty sets, c when exactly one is empty.
#include <Eigen/Core>
#include <vector>

#include "core/estimate.hpp"
#include "core/world.hpp"

namespace slambox {

enum class LandmarkMatching { kAuto, kById, kOptimal };

struct LandmarkMapOptions {
  LandmarkMatching matching = LandmarkMatching::kAuto;  ///< auto: by id when every estimated id is a true id
  double ospa_cutoff_m = 1.0;  ///< c [m]; an optimal-assignment match farther than c counts as spurious + missed
  double ospa_order = 2.0;     ///< p
};

struct LandmarkMatch {
  int estimate_index = 0;  ///< into Estimate::landmarks
  int true_index = 0;      ///< into World::landmarks
  double error_m = 0.0;    ///< after alignment
  double nees = 0.0;       ///< unaligned (the estimate's own frame); NaN without covariance
};

struct LandmarkMapResult {
  bool by_id = false;
  std::vector<LandmarkMatch> matches;
  double rmse_m = 0.0;  ///< over matches; NaN when there are none
  double ospa_m = 0.0;
  int spurious = 0;     ///< estimated landmarks without a true match
  int missed = 0;       ///< true landmarks without an estimated match
  double anees = 0.0;   ///< mean landmark NEES over matches with covariance; NaN if none
};

LandmarkMapResult EvaluateLandmarkMap(const std::vector<LandmarkEstimate>& estimated,
                                      const std::vector<TrueLandmark>& truth, const SE2& T_gt_est,
                                      const LandmarkMapOptions& options = {});

/// OSPA distance between two point sets (cutoff c [m], order p).
double OspaDistance(const std::vector<Eigen::Vector2d>& X, const std::vector<Eigen::Vector2d>& Y, double cutoff_m,
                    double order);

}  // namespace slambox
