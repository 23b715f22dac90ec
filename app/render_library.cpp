#include "app/render_library.hpp"

#include <dlfcn.h>

#include <stdexcept>

#include "app/plugins.hpp"

namespace slambox {

const RenderLibrary& Render() {
  static const RenderLibrary* library = [] {
    const std::string file = SlamboxLibraryDir() + "/slambox-render.so";
    void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) throw std::runtime_error("cannot load the renderer " + file + ": " + dlerror() + " (rebuild slambox)");
    using Entry = const RenderLibrary* (*)();
    auto* entry = reinterpret_cast<Entry>(dlsym(handle, "slambox_render_library"));
    const RenderLibrary* lib = entry ? entry() : nullptr;
    if (!lib || lib->abi != kRenderLibraryAbi)
      throw std::runtime_error("the renderer " + file + " is from another slambox build (rebuild slambox)");
    return lib;
  }();
  return *library;
}

}  // namespace slambox
