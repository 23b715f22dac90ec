// The MRPT peers as a module plugin (slambox-mrpt.so): the slambox executable links no
// MRPT and loads this only when an mrpt-* module is named, or a rawlog is converted or
// exported (the second entry point, slambox_rawlog_format: core/laser_log.hpp).
#include "core/laser_log.hpp"
#include "core/plugin.hpp"
#include "slam/mrpt/mrpt_ekf_slam.hpp"
#include "slam/mrpt/mrpt_graphslam.hpp"
#include "slam/mrpt/mrpt_icp_slam.hpp"
#include "slam/mrpt/mrpt_rawlog.hpp"
#include "slam/mrpt/mrpt_rbpf_slam.hpp"

namespace {
std::vector<slambox::ModuleInfo> MrptModules() {
  return {slambox::MrptIcpSlamModule(), slambox::MrptEkfSlamModule(), slambox::MrptRbpfSlamModule(),
          slambox::MrptGraphSlamModule()};
}
}  // namespace

SLAMBOX_PLUGIN("slambox-mrpt", MrptModules)

extern "C" __attribute__((visibility("default"))) const slambox::LogFormatEntry* slambox_rawlog_format() {
  using Read = slambox::LaserLog (*)(const std::string&);
  static const slambox::LogFormatEntry entry{SLAMBOX_API_VERSION, static_cast<Read>(&slambox::mrpt_bridge::ReadRawlog),
                                             &slambox::mrpt_bridge::WriteRawlog};
  return &entry;
}
