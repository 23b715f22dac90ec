#include "slam/icp_params.hpp"

#include "slam/icp_target.hpp"

namespace slambox {

const EnumNames<IcpMetric>& IcpMetricNames() {
  static const EnumNames<IcpMetric> names = {{IcpMetric::kPointToPoint, "point-to-point"},
                                             {IcpMetric::kPointToLine, "point-to-line"}};
  return names;
}
const EnumNames<IcpCorrespondence>& IcpCorrespondenceNames() {
  static const EnumNames<IcpCorrespondence> names = {{IcpCorrespondence::kKdTree, "kdtree"},
                                                     {IcpCorrespondence::kProjection, "projection"}};
  return names;
}
const EnumNames<IcpRobustKernel>& IcpRobustKernelNames() {
  static const EnumNames<IcpRobustKernel> names = {{IcpRobustKernel::kNone, "none"},
                                                   {IcpRobustKernel::kHuber, "huber"},
                                                   {IcpRobustKernel::kGemanMcClure, "geman-mcclure"}};
  return names;
}

void BindIcpParams(IcpConfig& c, ParamBinder& b, const std::string& p) {
  b.Bind(p + "metric", c.metric, IcpMetricNames(), "ICP error metric");
  b.Bind(p + "correspondence", c.correspondence, IcpCorrespondenceNames(),
         "nearest neighbours by kd-tree, or by projection into the reference scan's beams");
  b.Bind(p + "robust_kernel", c.robust_kernel, IcpRobustKernelNames(), "IRLS weights on residuals");
  b.Bind(p + "robust_scale_m", c.robust_scale_m, "m", "Huber corner / Geman-McClure scale", Above(0));
  b.Bind(p + "max_iterations", c.max_iterations, "-", "ICP iteration cap", AtLeast(1));
  b.Bind(p + "convergence_translation_m", c.convergence_translation_m, "m", "converged when a step moves less");
  b.Bind(p + "convergence_rotation_rad", c.convergence_rotation_rad, "rad", "converged when a step turns less");
  b.Bind(p + "max_correspondence_m", c.max_correspondence_m, "m", "distance gate on pairs (initial gate if adaptive)",
         Above(0));
  b.Bind(p + "trim_fraction", c.trim_fraction, "-", "drop this fraction of the worst pairs, in [0, 1)",
         Range{.min = 0, .max = 1, .max_open = true});
  b.Bind(p + "projection_window_beams", c.projection_window_beams, "beams", "search +- this many beams (<= 16)",
         Between(0, IcpTarget::kBeamPad));
  b.Bind(p + "min_inliers", c.min_inliers, "-", "fewer pairs: ICP fails and odometry is used");
  b.Bind(p + "degeneracy_eigenvalue_ratio", c.degeneracy_eigenvalue_ratio, "-",
         "Hessian eigenvalue / inliers below this marks a degenerate direction (Zhang 2016)");
  b.Bind(p + "remap_degenerate", c.remap_degenerate, "-", "keep the odometry guess along degenerate directions");
  b.Bind(p + "sigma_residual_m", c.sigma_residual_m, "m", "residual std for the covariance (0 = from RMS)");
}

}  // namespace slambox
