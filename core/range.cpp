#include "core/range.hpp"

#include <sstream>

namespace slambox {

namespace {
std::string Format(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}
}  // namespace

Range AtLeast(double v) { return Range{.min = v}; }
Range Above(double v) { return Range{.min = v, .min_open = true}; }
Range Between(double lo, double hi) { return Range{.min = lo, .max = hi}; }

bool InRange(const Range& r, double v) {
  return (r.min_open ? v > r.min : v >= r.min) && (r.max_open ? v < r.max : v <= r.max);
}

std::string Describe(const Range& r) {
  std::string lo = r.min > -1e299 ? (r.min_open ? "> " : ">= ") + Format(r.min) : "";
  std::string hi = r.max < 1e299 ? (r.max_open ? "< " : "<= ") + Format(r.max) : "";
  if (!lo.empty() && !hi.empty()) return lo + " and " + hi;
  return lo.empty() ? hi : lo;
}

}  // namespace slambox
