#pragma once
// Closed or open bounds on a number, shared by the scenario reader (sim/scenario_yaml) and
// the module parameter binder (core/params): one rule, one message text.
#include <string>

namespace slambox {

/// Defaults accept any finite value.
struct Range {
  double min = -1e300;
  double max = 1e300;
  bool min_open = false;  ///< true: value must be > min
  bool max_open = false;  ///< true: value must be < max
};
Range AtLeast(double v);
Range Above(double v);
Range Between(double lo, double hi);

bool InRange(const Range& r, double v);
/// ">= 0", "> 0 and <= 1", "" for an unbounded range.
std::string Describe(const Range& r);

}  // namespace slambox
