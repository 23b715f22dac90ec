// A plugin built for another API version: refused before its modules are touched.
#include "core/plugin.hpp"

namespace {
std::vector<slambox::ModuleInfo> Modules() { std::abort(); }  // never called
}  // namespace

extern "C" __attribute__((visibility("default"))) const slambox::PluginEntry* slambox_plugin_entry() {
  static const slambox::PluginEntry entry{SLAMBOX_API_VERSION + 1, "future-plugin", &Modules};
  return &entry;
}
