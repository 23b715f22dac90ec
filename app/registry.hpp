#pragma once
// Every SLAM module, found by name. Adding a module = one line in registry.cpp.
#include <string>
#include <vector>

#include "core/slam_module.hpp"

namespace slambox {

const std::vector<ModuleInfo>& AllModules();
/// Throws InputError listing the known names when `name` is unknown.
const ModuleInfo& FindModule(const std::string& name);
/// True when the stream carries every sensor the module needs.
/// True when the sensors (and, for localization, a known map) are there for the module.
bool SensorsAllow(const ModuleInfo& module, const SensorSuite& sensors, bool has_map = true);

}  // namespace slambox
