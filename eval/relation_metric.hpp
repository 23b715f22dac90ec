#pragma once
// Kümmerle et al. 2009 ("On measuring the accuracy of SLAM algorithms", eq. 2): for
// relations (i, j) with true relative pose d*_ij and estimated d_ij, the error is
// e_ij = d*_ij^-1 d_ij (the RPE matrix E_ij); published tables give the mean ± std of the
// absolute translational [m] and rotational [deg] errors and of their squares. Here the
// relations are the RPE pairs; std is the population std (ddof 0).
#include <vector>

#include "core/se2.hpp"
#include "eval/rpe.hpp"

namespace slambox {

struct RelationMetric {
  int relations = 0;
  double trans_mean_m = 0.0, trans_std_m = 0.0;
  double trans_sq_mean_m2 = 0.0, trans_sq_std_m2 = 0.0;
  double rot_mean_deg = 0.0, rot_std_deg = 0.0;
  double rot_sq_mean_deg2 = 0.0, rot_sq_std_deg2 = 0.0;
};

/// From per-relation errors (e.g. RpeResult's translation_m and rotation_deg).
RelationMetric ComputeRelationMetric(const std::vector<double>& translation_m, const std::vector<double>& rotation_deg);

}  // namespace slambox
