#pragma once
// Every SLAM module, found by name: the built-ins (one line each in registry.cpp), the
// modules of plugins loaded at run time (`--plugin`, `plugins:`, SLAMBOX_PLUGIN_PATH), and
// those of the plugins shipped with slambox (the MRPT peers), known from their manifests
// and loaded only when one of their modules is named, or all modules are asked for.
#include <string>
#include <vector>

#include "core/slam_module.hpp"

namespace slambox {

/// Every module that can run, in listing order. Loads the shipped plugins; one that fails
/// to load is left out (ListModules says why).
std::vector<ModuleInfo> AllModules();
/// Loads a shipped plugin when `name` is one of its modules. Throws InputError listing the
/// known names when `name` is unknown, or with the reason when its plugin cannot load.
/// The reference stays valid for the process's life.
const ModuleInfo& FindModule(const std::string& name);
/// True when the sensors (and, for localization, a known map) are there for the module.
bool SensorsAllow(const ModuleInfo& module, const SensorSuite& sensors, bool has_map = true);

/// Opens a module plugin and registers its modules; loading the same file again does
/// nothing. Throws InputError (see OpenPlugin) or when a module's name is taken.
void LoadPlugin(const std::string& path);
/// Registers one module made at run time; `origin` names where it comes from (messages,
/// `slambox algorithms`). Throws InputError when the name is taken.
void RegisterModule(ModuleInfo module, const std::string& origin);

/// One line of `slambox algorithms`; shipped plugins are not loaded for it.
struct ModuleListing {
  std::string name;
  std::string description;
  SensorNeeds needs;
  std::string origin;       ///< empty for a built-in, else "plugin NAME"
  std::string unavailable;  ///< why it cannot run (its plugin is missing or does not load); empty: it can
  bool in_all = true;       ///< ModuleInfo::in_all: false, run only when named
};
std::vector<ModuleListing> ListModules();

}  // namespace slambox
