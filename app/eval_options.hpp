#pragma once
// The trajectory options of `slambox eval` and of Python's slambox.evaluate(), checked in
// one place: the same choices, the same validation, messages spelled for each caller
// (`--delta-unit f` on the command line, `delta_unit='f'` in Python).
#include <string>

#include "eval/evaluate.hpp"

namespace slambox {

struct EvalChoices {
  std::string align = "none";     ///< none | se2 (Umeyama, evo -a) | origin (evo --align_origin)
  double delta = 1.0;             ///< RPE step, in delta_unit
  std::string delta_unit = "m";   ///< m (metres) | f (frames) | d (degrees)
  bool all_pairs = false;         ///< evo --all_pairs
  bool pairs_from_reference = false;
  double t_max_diff_s = 0.01;     ///< [s] timestamp matching window
  bool interpolate = false;       ///< interpolate ground truth at the estimate's times
};

enum class OptionSpelling { kCommandLine, kPython };

/// EvalOptions for `choices`; throws InputError naming the option (as `spelling` writes it)
/// with the fix, for an unknown alignment or unit, a delta <= 0, a fractional frame delta,
/// a degree delta > 180 or a negative t_max_diff_s.
EvalOptions TrajectoryEvalOptions(const EvalChoices& choices, OptionSpelling spelling);

/// Throws InputError (at `est_where`) when no estimate pose matched the ground truth.
void RequireMatchedPoses(const Metrics& metrics, const EvalChoices& choices, const std::string& est_where,
                         OptionSpelling spelling);

}  // namespace slambox
