#include "app/rawlog_format.hpp"

#include <dlfcn.h>

#include "app/plugins.hpp"
#include "core/error.hpp"
#include "core/version.hpp"

namespace slambox {

const LogFormatEntry& RawlogFormat() {
  static const LogFormatEntry* entry = nullptr;
  if (entry) return *entry;
  const std::string file = ShippedPluginDir() + "/slambox-mrpt.so";
  const std::string fix = "build slambox with MRPT (libmrpt-dev; the slambox_mrpt_plugin target) or reinstall it";
  void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);  // never closed: its code is used until exit
  if (!handle) throw InputError(file, 0, std::string("rawlogs need the MRPT plugin, which does not load: ") + dlerror(), fix);
  using Entry = const LogFormatEntry* (*)();
  const auto get = reinterpret_cast<Entry>(dlsym(handle, SLAMBOX_RAWLOG_FORMAT_SYMBOL));
  if (!get) throw InputError(file, 0, "the MRPT plugin has no rawlog entry point (" SLAMBOX_RAWLOG_FORMAT_SYMBOL ")", fix);
  const LogFormatEntry* e = get();
  if (e->api_version != SLAMBOX_API_VERSION)
    throw InputError(file, 0, "the MRPT plugin is for API version " + std::to_string(e->api_version) + ", slambox has " +
                                  std::to_string(SLAMBOX_API_VERSION), fix);
  entry = e;
  return *entry;
}

}  // namespace slambox
