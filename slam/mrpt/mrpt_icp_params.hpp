#pragma once
// The CICP settings (mrpt::slam::CICP::TConfigParams) a peer exposes as `icp_*` keys, in
// one place for every module that runs MRPT's ICP (mrpt-icp-slam's alignment,
// mrpt-rbpf-slam's optimal proposal). No MRPT types here; slam/mrpt/mrpt_convert.hpp
// turns them into MRPT's.
#include <string>

#include "core/params.hpp"

namespace slambox {

/// MRPT's icpClassic or icpLevenbergMarquardt.
enum class MrptIcpAlgorithm { kClassic, kLevenbergMarquardt };
/// Its names ("classic", "lm").
const EnumNames<MrptIcpAlgorithm>& MrptIcpAlgorithmNames();

struct MrptIcpParams {  ///< defaults: MRPT's own
  MrptIcpAlgorithm algorithm = MrptIcpAlgorithm::kClassic;  ///< classic | lm
  int max_iterations = 40;
  double threshold_dist_m = 0.75;   ///< initial pairing distance
  double threshold_ang_deg = 0.15;  ///< pairing distance grows by this angle times range
  double alfa = 0.5;                ///< threshold shrink factor at convergence
  double smallest_threshold_dist_m = 0.1;
  int points_decimation = 5;        ///< use every n-th correspondence
};

/// Binds icp_algorithm, icp_max_iterations, ..., icp_points_decimation; `role` starts
/// each description (e.g. "optimal proposal: ").
void BindIcpParams(MrptIcpParams& p, ParamBinder& b, const std::string& role);

}  // namespace slambox
