#pragma once
// Loop-closure quality against ground truth. A proposed closure (t_from, t_to, T_from_to)
// is correct when T_err = T_true^-1 T_measured, T_true = Q(t_from)^-1 Q(t_to), has
// |t(T_err)| <= 0.2 m and |angle(T_err)| <= 2 deg (Cartographer's loop-closure test
// style). Precision = correct accepted / accepted.
// Recall is measured against true revisits: ground truth is sampled every
// sample_spacing_m of travel; a sample is a revisit when it lies within revisit_radius_m
// of a sample passed at least min_revisit_travel_m of travel earlier; consecutive
// revisit samples form one revisit episode. An episode is recalled when a correct
// accepted closure's later time falls inside it (widened to its neighbouring samples).
#include <vector>

#include "core/estimate.hpp"
#include "core/stream.hpp"

namespace slambox {

struct LoopClosureOptions {
  double max_translation_error_m = 0.2;
  double max_rotation_error_deg = 2.0;
  double revisit_radius_m = 1.0;
  double min_revisit_travel_m = 10.0;
  double sample_spacing_m = 0.25;
};

struct LoopClosureResult {
  int proposed = 0;
  int accepted = 0;
  int accepted_correct = 0;
  double precision = 0.0;  ///< NaN when none was accepted
  int revisit_episodes = 0;
  int recalled_episodes = 0;
  double recall = 0.0;     ///< NaN when the run has no revisit
  std::vector<char> correct;  ///< per proposed closure
};

LoopClosureResult EvaluateLoopClosures(const std::vector<LoopClosureRecord>& closures,
                                       const std::vector<StampedPose>& groundtruth,
                                       const LoopClosureOptions& options = {});

/// Revisit episodes as [t_begin_s, t_end_s] intervals (see above).
std::vector<std::pair<double, double>> RevisitEpisodes(const std::vector<StampedPose>& groundtruth,
                                                       const LoopClosureOptions& options = {});

}  // namespace slambox
