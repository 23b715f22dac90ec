#pragma once
// Module plugins (core/plugin.hpp) opened at run time, and the manifests that let slambox
// list a shipped plugin's modules without loading it (the MRPT peers: loading MRPT costs
// ~300 shared libraries). The registry (app/registry.hpp) decides when to load what.
#include <string>
#include <vector>

#include "core/slam_module.hpp"

namespace slambox {

struct LoadedPlugin {
  std::string path;  ///< as given
  std::string name;  ///< PluginEntry::name
  std::vector<ModuleInfo> modules;
};

/// dlopens `path` (never unloaded: its modules' code lives there) and reads its entry point.
/// Throws InputError naming the file: missing, not a shared library, no slambox entry
/// point, built for another SLAMBOX_API_VERSION, a module without a name, a name twice.
LoadedPlugin OpenPlugin(const std::string& path);

/// A module a plugin's manifest declares: what `slambox algorithms` shows without loading it.
struct ManifestModule {
  std::string name;
  std::string description;
  SensorNeeds needs;
  bool in_all = true;  ///< ModuleInfo::in_all
  std::string plugin_name;
  std::string plugin_path;  ///< the .so, next to the manifest
};

/// The manifest of `plugin` (JSON text); `file_name` is the .so's name next to it.
std::string ManifestJson(const LoadedPlugin& plugin, const std::string& file_name);
/// Every `*.manifest.json` in `dir`, sorted by file name (no folder: none). Throws
/// InputError naming the manifest when one is malformed or for another API version.
std::vector<ManifestModule> ReadManifests(const std::string& dir);

/// lib/slambox beside the executable's folder (installed: PREFIX/bin/slambox ->
/// PREFIX/lib/slambox; build tree: build/app/slambox -> build/lib/slambox): the renderer
/// library, and in plugins/ the shipped plugins.
std::string SlamboxLibraryDir();
std::string ShippedPluginDir();
/// For a program that is not slambox (the Python module inside python3): where its
/// lib/slambox is. Call before the first module, plugin or figure is looked up.
void SetSlamboxLibraryDir(const std::string& dir);

/// The plugin files a SLAMBOX_PLUGIN_PATH value names: ':'-separated files, or folders
/// (each folder's *.so, sorted). Throws InputError for an entry that does not exist.
std::vector<std::string> PluginPathFiles(const std::string& value);

}  // namespace slambox
