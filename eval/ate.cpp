#include "eval/ate.hpp"

#include <cassert>
#include <cmath>

namespace slambox {

AbsoluteErrors AbsoluteTrajectoryErrors(const std::vector<SE2>& gt, const std::vector<SE2>& est) {
  assert(gt.size() == est.size());
  AbsoluteErrors e;
  e.translation_m.reserve(gt.size());
  e.heading_rad.reserve(gt.size());
  for (size_t i = 0; i < gt.size(); ++i) {
    const double dx = est[i].x - gt[i].x, dy = est[i].y - gt[i].y;
    e.translation_m.push_back(std::sqrt(dx * dx + dy * dy));
    e.heading_rad.push_back(NormalizeAngle(est[i].theta - gt[i].theta));
  }
  return e;
}

std::vector<double> AbsDegrees(const std::vector<double>& angles_rad) {
  std::vector<double> out;
  out.reserve(angles_rad.size());
  for (double a : angles_rad) out.push_back(std::abs(a) * 180.0 / M_PI);
  return out;
}

}  // namespace slambox
