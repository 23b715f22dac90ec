#include "app/eval_options.hpp"

#include <cmath>

#include "core/error.hpp"

namespace slambox {

namespace {

/// "--delta-unit" / "delta_unit" (t_max_diff_s is `--t-max-diff` on the command line).
std::string Name(const std::string& option, OptionSpelling spelling) {
  if (spelling == OptionSpelling::kPython) return option;
  std::string flag = option == "t_max_diff_s" ? "t_max_diff" : option;
  for (char& c : flag)
    if (c == '_') c = '-';
  return "--" + flag;
}

/// "--delta 10" / "delta=10"; a text value is quoted in Python ("delta_unit='f'").
std::string Example(const std::string& option, const std::string& value, OptionSpelling spelling, bool text = false) {
  if (spelling == OptionSpelling::kPython) return option + "=" + (text ? "'" + value + "'" : value);
  return Name(option, spelling) + " " + value;
}

std::string Flag(const std::string& option, OptionSpelling spelling) {
  return spelling == OptionSpelling::kPython ? option + "=True" : Name(option, spelling);
}

}  // namespace

EvalOptions TrajectoryEvalOptions(const EvalChoices& c, OptionSpelling s) {
  EvalOptions o;
  if (c.align == "none") o.align = AlignMode::kNone;
  else if (c.align == "se2") o.align = AlignMode::kSE2;
  else if (c.align == "origin") o.align = AlignMode::kOrigin;
  else throw InputError(Name("align", s), 0, "unknown alignment '" + c.align + "'", "use none, se2 or origin");
  if (!ParseDeltaUnit(c.delta_unit, o.rpe.unit))
    throw InputError(Name("delta_unit", s), 0, "unknown delta unit '" + c.delta_unit + "'", "use m, f or d");
  if (!(c.delta > 0.0))
    throw InputError(Name("delta", s), 0, "delta must be positive", "give e.g. " + Example("delta", "1", s));
  if (o.rpe.unit == DeltaUnit::kFrames && c.delta != std::floor(c.delta))
    throw InputError(Name("delta", s), 0, "a delta in frames must be an integer",
                     "give e.g. " + Example("delta", "10", s) + (s == OptionSpelling::kPython ? ", " : " ") +
                         Example("delta_unit", "f", s, true));
  if (o.rpe.unit == DeltaUnit::kDegrees && c.delta > 180.0)
    throw InputError(Name("delta", s), 0, "a delta in degrees must be within (0, 180]",
                     "give e.g. " + Example("delta", "90", s));
  if (!(c.t_max_diff_s >= 0.0))
    throw InputError(Name("t_max_diff_s", s), 0, "must be >= 0", "give e.g. " + Example("t_max_diff_s", "0.01", s));
  o.rpe.delta = c.delta;
  o.rpe.all_pairs = c.all_pairs;
  o.rpe.pairs_from_reference = c.pairs_from_reference;
  o.max_time_diff_s = c.t_max_diff_s;
  o.interpolate_groundtruth = c.interpolate;
  return o;
}

void RequireMatchedPoses(const Metrics& metrics, const EvalChoices& c, const std::string& est_where,
                         OptionSpelling s) {
  if (metrics.matched_poses.value_or(0) > 0) return;
  throw InputError(est_where, 0, "no timestamp matches the ground truth within " + std::to_string(c.t_max_diff_s) + " s",
                   "check that both use the same clock, or raise " + Name("t_max_diff_s", s) + " / use " +
                       Flag("interpolate", s));
}

}  // namespace slambox
