#pragma once
// The CMetricMapBuilderRBPF options mrpt-rbpf-slam builds from its config, apart from the
// module so they can be compared with what MRPT's own reader makes of an .ini
// (TConstructionOptions::loadFromConfigFile; tests/mrpt/rbpf_points_test.cpp does that
// for gridmapping_RBPF_ICPbased_intel.ini). MRPT types: for slam/mrpt and tests/mrpt only.
#include <mrpt/slam/CMetricMapBuilderRBPF.h>

#include "slam/mrpt/mrpt_rbpf_slam.hpp"

namespace slambox {

/// Maps, particle filter, prediction and CICP options as the module runs MRPT (verbosity
/// LVL_ERROR; fields the module has no key for keep MRPT's defaults).
mrpt::slam::CMetricMapBuilderRBPF::TConstructionOptions MakeMrptRbpfOptions(const MrptRbpfSlamConfig& c);

}  // namespace slambox
