// slambox_plugin_manifest PLUGIN.so OUT.manifest.json: writes a plugin's manifest (its
// modules' names, sensor needs, descriptions) at build time, so that `slambox algorithms`
// lists them without loading the plugin.
#include <filesystem>
#include <iostream>

#include "app/plugins.hpp"
#include "core/atomic_file.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: slambox_plugin_manifest PLUGIN.so OUT.manifest.json\n";
    return 2;
  }
  try {
    const slambox::LoadedPlugin plugin = slambox::OpenPlugin(argv[1]);
    slambox::WriteFileAtomic(argv[2], slambox::ManifestJson(plugin, std::filesystem::path(argv[1]).filename().string()));
  } catch (const std::exception& e) {
    std::cerr << "slambox_plugin_manifest: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
