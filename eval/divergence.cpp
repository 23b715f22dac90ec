#include "eval/divergence.hpp"

#include <cmath>
#include <sstream>

namespace slambox {

namespace {
std::string At(double t_s) {
  std::ostringstream s;
  s << " at t=" << t_s << " s";
  return s.str();
}
}  // namespace

DivergenceResult DetectDivergence(const std::vector<PoseEstimate>& traj, const std::vector<int>& estimate_index,
                                  const std::vector<double>& error_m, const std::vector<double>& distance_m,
                                  const DivergenceOptions& o) {
  DivergenceResult r;
  auto fail = [&](const std::string& why) {
    r.diverged = true;
    r.reason = why;
    return r;
  };
  for (const auto& p : traj) {
    if (!std::isfinite(p.pose.x) || !std::isfinite(p.pose.y) || !std::isfinite(p.pose.theta))
      return fail("non-finite pose" + At(p.t_s));
    if (!p.has_covariance) continue;
    if (!p.covariance.allFinite()) return fail("non-finite covariance" + At(p.t_s));
    const double pos_var = std::max(p.covariance(0, 0), p.covariance(1, 1));
    if (pos_var > o.max_position_variance_m2) {
      std::ostringstream s;
      s << "exploding covariance: position variance " << pos_var << " m^2 > " << o.max_position_variance_m2
        << At(p.t_s);
      return fail(s.str());
    }
    if (p.covariance(2, 2) > o.max_heading_variance_rad2) {
      std::ostringstream s;
      s << "exploding covariance: heading variance " << p.covariance(2, 2) << " rad^2 > "
        << o.max_heading_variance_rad2 << At(p.t_s);
      return fail(s.str());
    }
  }
  for (size_t k = 0; k < error_m.size(); ++k) {
    const double limit = o.runaway_factor * distance_m[k] + o.runaway_margin_m;
    if (error_m[k] > limit) {
      std::ostringstream s;
      s << "runaway error: position error " << error_m[k] << " m > " << limit << " m after " << distance_m[k]
        << " m of travel" << At(traj[estimate_index[k]].t_s);
      return fail(s.str());
    }
  }
  return r;
}

}  // namespace slambox
