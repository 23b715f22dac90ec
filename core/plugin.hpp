#pragma once
// The module plugin entry point. A plugin is a shared library that adds SLAM modules to
// slambox at run time (`slambox run/sweep --plugin PATH.so`, `plugins:` in a sweep file,
// SLAMBOX_PLUGIN_PATH). It exports exactly one symbol, made by SLAMBOX_PLUGIN:
//
//   #include "core/plugin.hpp"
//   std::vector<slambox::ModuleInfo> MyModules() { return {MakeModuleInfo<My, MyConfig>(...)}; }
//   SLAMBOX_PLUGIN("my-plugin", MyModules)
//
// slambox reads PluginEntry::api_version first and refuses a plugin built for another
// SLAMBOX_API_VERSION before it touches anything else. The API (this header,
// slam_module.hpp, params.hpp, stream.hpp, sensors.hpp, estimate.hpp, se2.hpp) is
// documented in docs/plugins.md; plugins are C++ and must be built with the same compiler
// family and standard library as slambox (GCC/libstdc++ on Debian 12).
#include <vector>

#include "core/slam_module.hpp"
#include "core/version.hpp"

namespace slambox {

struct PluginEntry {
  int api_version;     ///< SLAMBOX_API_VERSION the plugin was built with; always the first member
  const char* name;    ///< the plugin's name, for messages
  std::vector<ModuleInfo> (*modules)();  ///< the modules it adds (names must not clash)
};

}  // namespace slambox

/// The entry point's symbol name (extern "C", so it is the same for every compiler).
#define SLAMBOX_PLUGIN_ENTRY_SYMBOL "slambox_plugin_entry"

/// Defines the plugin's one exported entry point. `modules_function` is a
/// `std::vector<slambox::ModuleInfo>()` function.
#define SLAMBOX_PLUGIN(plugin_name, modules_function)                                           \
  extern "C" __attribute__((visibility("default"))) const ::slambox::PluginEntry* slambox_plugin_entry() { \
    static const ::slambox::PluginEntry entry{SLAMBOX_API_VERSION, plugin_name, &modules_function};       \
    return &entry;                                                                                \
  }
