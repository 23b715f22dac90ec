#pragma once
// Absolute trajectory error (evo's APE): per matched pose, the translation error
// |t_est - t_gt| [m] (evo: translation_part) and the heading error
// wrap(theta_est - theta_gt) [rad] (evo: angle_deg, |log(R_gt^T R_est)|). The heading is a
// wrapped difference, never acos of a trace: identical poses give exactly 0 (evo #216).
#include <vector>

#include "core/se2.hpp"

namespace slambox {

struct AbsoluteErrors {
  std::vector<double> translation_m;  ///< >= 0
  std::vector<double> heading_rad;    ///< signed, in [-pi, pi)
};

/// Index-matched poses of equal length.
AbsoluteErrors AbsoluteTrajectoryErrors(const std::vector<SE2>& gt, const std::vector<SE2>& est);

/// Absolute values converted to degrees.
std::vector<double> AbsDegrees(const std::vector<double>& angles_rad);

}  // namespace slambox
