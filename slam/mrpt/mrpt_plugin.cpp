// The MRPT peers as a module plugin (slambox-mrpt.so): the slambox executable links no
// MRPT and loads this only when an mrpt-* module is named.
#include "core/plugin.hpp"
#include "slam/mrpt/mrpt_ekf_slam.hpp"
#include "slam/mrpt/mrpt_icp_slam.hpp"
#include "slam/mrpt/mrpt_rbpf_slam.hpp"

namespace {
std::vector<slambox::ModuleInfo> MrptModules() {
  return {slambox::MrptIcpSlamModule(), slambox::MrptEkfSlamModule(), slambox::MrptRbpfSlamModule()};
}
}  // namespace

SLAMBOX_PLUGIN("slambox-mrpt", MrptModules)
