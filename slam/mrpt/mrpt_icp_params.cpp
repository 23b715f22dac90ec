#include "slam/mrpt/mrpt_icp_params.hpp"

namespace slambox {

const EnumNames<MrptIcpAlgorithm>& MrptIcpAlgorithmNames() {
  static const EnumNames<MrptIcpAlgorithm> kNames = {{MrptIcpAlgorithm::kClassic, "classic"},
                                                    {MrptIcpAlgorithm::kLevenbergMarquardt, "lm"}};
  return kNames;
}

void BindIcpParams(MrptIcpParams& p, ParamBinder& b, const std::string& role) {
  b.Bind("icp_algorithm", p.algorithm, MrptIcpAlgorithmNames(), role + "CICP variant: icpClassic or icpLevenbergMarquardt");
  b.Bind("icp_max_iterations", p.max_iterations, "-", role + "CICP maxIterations", AtLeast(1));
  b.Bind("icp_threshold_dist_m", p.threshold_dist_m, "m", role + "CICP thresholdDist: initial pairing distance", Above(0));
  b.Bind("icp_threshold_ang_deg", p.threshold_ang_deg, "deg", role + "CICP thresholdAng: pairing distance per metre of range",
         AtLeast(0));
  b.Bind("icp_alfa", p.alfa, "-", role + "CICP ALFA: threshold shrink factor at convergence", Between(0, 1));
  b.Bind("icp_smallest_threshold_dist_m", p.smallest_threshold_dist_m, "m", role + "CICP smallestThresholdDist", Above(0));
  b.Bind("icp_points_decimation", p.points_decimation, "-", role + "CICP corresponding_points_decimation", AtLeast(1));
}

}  // namespace slambox
