#include "slam/icp_params.hpp"

#include "core/error.hpp"

namespace slambox {

void BindIcpParams(IcpConfig& c, IcpChoices& k, ParamBinder& b, const std::string& p) {
  b.Bind(p + "metric", k.metric, {"point-to-point", "point-to-line"}, "ICP error metric");
  b.Bind(p + "correspondence", k.correspondence, {"kdtree", "projection"},
         "nearest neighbours by kd-tree, or by projection into the reference scan's beams");
  b.Bind(p + "robust_kernel", k.robust_kernel, {"none", "huber", "geman-mcclure"}, "IRLS weights on residuals");
  b.Bind(p + "robust_scale_m", c.robust_scale_m, "m", "Huber corner / Geman-McClure scale");
  b.Bind(p + "max_iterations", c.max_iterations, "-", "ICP iteration cap");
  b.Bind(p + "convergence_translation_m", c.convergence_translation_m, "m", "converged when a step moves less");
  b.Bind(p + "convergence_rotation_rad", c.convergence_rotation_rad, "rad", "converged when a step turns less");
  b.Bind(p + "max_correspondence_m", c.max_correspondence_m, "m", "distance gate on pairs (initial gate if adaptive)");
  b.Bind(p + "trim_fraction", c.trim_fraction, "-", "drop this fraction of the worst pairs, in [0, 1)");
  b.Bind(p + "projection_window_beams", c.projection_window_beams, "beams", "search +- this many beams (<= 16)");
  b.Bind(p + "min_inliers", c.min_inliers, "-", "fewer pairs: ICP fails and odometry is used");
  b.Bind(p + "degeneracy_eigenvalue_ratio", c.degeneracy_eigenvalue_ratio, "-",
         "Hessian eigenvalue / inliers below this marks a degenerate direction (Zhang 2016)");
  b.Bind(p + "remap_degenerate", c.remap_degenerate, "-", "keep the odometry guess along degenerate directions");
  b.Bind(p + "sigma_residual_m", c.sigma_residual_m, "m", "residual std for the covariance (0 = from RMS)");
}

IcpConfig ResolveIcpConfig(IcpConfig c, const IcpChoices& k, const std::string& module) {
  c.metric = ParseIcpMetric(k.metric);
  c.correspondence = ParseIcpCorrespondence(k.correspondence);
  c.robust_kernel = ParseIcpRobustKernel(k.robust_kernel);
  const std::string where = "--set algo." + module;
  if (c.max_iterations < 1) throw InputError(where + ".max_iterations", 0, "must be >= 1", "give a positive count");
  if (c.trim_fraction < 0 || c.trim_fraction >= 1)
    throw InputError(where + ".trim_fraction", 0, "must be in [0, 1)", "e.g. 0.1");
  if (c.projection_window_beams < 0 || c.projection_window_beams > IcpTarget::kBeamPad)
    throw InputError(where + ".projection_window_beams", 0, "must be in [0, 16]", "e.g. 1");
  if (c.max_correspondence_m <= 0)
    throw InputError(where + ".max_correspondence_m", 0, "must be > 0", "e.g. 0.5");
  if (c.robust_scale_m <= 0) throw InputError(where + ".robust_scale_m", 0, "must be > 0", "e.g. 0.05");
  return c;
}

}  // namespace slambox
