#include "app/registry.hpp"

#include "app/exec_module.hpp"
#include "core/error.hpp"
#include "slam/dead_reckoning.hpp"
#include "slam/ekf_slam.hpp"
#include "slam/fastslam.hpp"
#include "slam/graphslam.hpp"
#include "slam/icp_localization.hpp"
#include "slam/icp_odometry.hpp"
#include "slam/icp_poseslam.hpp"
#include "slam/mcl.hpp"
#include "slam/mrpt/mrpt_ekf_slam.hpp"
#include "slam/mrpt/mrpt_icp_slam.hpp"
#include "slam/mrpt/mrpt_rbpf_slam.hpp"

namespace slambox {

const std::vector<ModuleInfo>& AllModules() {
  static const std::vector<ModuleInfo> modules = {
      DeadReckoningModule(),
      EkfSlamModule(),
      GraphSlamModule(),
      FastSlam1Module(),
      FastSlam2Module(),
      IcpOdometryModule(),
      IcpPoseSlamModule(),
      IcpLocalizationModule(),
      MclModule(),
      MrptIcpSlamModule(),
      MrptEkfSlamModule(),
      MrptRbpfSlamModule(),
  };
  return modules;
}

const ModuleInfo& FindModule(const std::string& name) {
  if (name.rfind("exec:", 0) == 0) return FindExecModule(name);  // a child process (docs/exec_protocol.md)
  for (const auto& m : AllModules())
    if (m.name == name) return m;
  std::string names;
  for (const auto& m : AllModules()) names += (names.empty() ? "" : ", ") + m.name;
  throw InputError("--algo", 0, "unknown algorithm '" + name + "'", "use one of: " + names + ", all, or exec:NAME");
}

bool SensorsAllow(const ModuleInfo& module, const SensorSuite& sensors, bool has_map) {
  return (!module.needs.odometry || sensors.odometry) && (!module.needs.lidar || sensors.lidar) &&
         (!module.needs.landmarks || sensors.landmarks) && (!module.needs.map || has_map);
}

}  // namespace slambox
