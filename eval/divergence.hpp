#pragma once
// Divergence: a module whose estimate is unusable is reported as data ("diverged" with a
// reason), never by throwing. Checked in time order; the first cause found is reported:
// a non-finite pose or covariance, a covariance whose position or heading variance
// exceeds its limit (exploding), or a position error that outruns the distance travelled
// (|e_k| > runaway_factor * d_k + runaway_margin_m, d_k the true distance so far: even a
// robot heading the wrong way stays within 2 d_k of the truth).
#include <string>
#include <vector>

#include "core/estimate.hpp"

namespace slambox {

struct DivergenceOptions {
  double max_position_variance_m2 = 1e6;   ///< [m^2] a 1 km standard deviation
  double max_heading_variance_rad2 = 1e4;  ///< [rad^2]
  double runaway_factor = 2.0;
  double runaway_margin_m = 10.0;          ///< [m]
};

struct DivergenceResult {
  bool diverged = false;
  std::string reason;
};

/// `position_error_m[k]` and `distance_m[k]` are at matched pose k, estimate_index[k] its
/// index into estimate.trajectory (as Association gives them).
DivergenceResult DetectDivergence(const std::vector<PoseEstimate>& trajectory, const std::vector<int>& estimate_index,
                                  const std::vector<double>& position_error_m, const std::vector<double>& distance_m,
                                  const DivergenceOptions& options = {});

}  // namespace slambox
