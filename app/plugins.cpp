#include "app/plugins.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "core/error.hpp"
#include "core/plugin.hpp"

namespace slambox {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr const char* kDocs = "see docs/plugins.md";

json NeedsJson(const SensorNeeds& n) {
  return {{"odometry", n.odometry}, {"lidar", n.lidar}, {"landmarks", n.landmarks}, {"map", n.map}};
}

}  // namespace

LoadedPlugin OpenPlugin(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw InputError(path, 0, "plugin file not found",
                     "give the path of a built plugin (a .so made with SLAMBOX_PLUGIN; " + std::string(kDocs) + ")");
  // A path without '/' would make dlopen search the library path instead of this file.
  const std::string file = fs::absolute(path).string();
  void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = dlerror();
    throw InputError(path, 0, std::string("not a loadable shared library: ") + (why ? why : "dlopen failed"),
                     "build the plugin as a shared library (add_library(NAME MODULE ...)) against this slambox; " +
                         std::string(kDocs));
  }
  using EntryFunction = const PluginEntry* (*)();
  auto* entry_fn = reinterpret_cast<EntryFunction>(dlsym(handle, SLAMBOX_PLUGIN_ENTRY_SYMBOL));
  if (!entry_fn)
    throw InputError(path, 0, "not a slambox plugin: it exports no " SLAMBOX_PLUGIN_ENTRY_SYMBOL "()",
                     "define the entry point with SLAMBOX_PLUGIN(\"name\", ModulesFunction) from core/plugin.hpp");
  const PluginEntry* entry = entry_fn();
  if (!entry)
    throw InputError(path, 0, "the plugin's entry point returned no entry", "return SLAMBOX_PLUGIN's entry");
  if (entry->api_version != SLAMBOX_API_VERSION)
    throw InputError(path, 0,
                     "plugin built for slambox API version " + std::to_string(entry->api_version) +
                         ", this slambox has API version " + std::to_string(SLAMBOX_API_VERSION),
                     "rebuild the plugin against this slambox's SDK (cmake --install, find_package(slambox))");
  LoadedPlugin plugin;
  plugin.path = path;
  plugin.name = entry->name ? entry->name : "";
  try {
    plugin.modules = entry->modules();
  } catch (const std::exception& e) {
    throw InputError(path, 0, std::string("the plugin failed to list its modules: ") + e.what(),
                     "fix the plugin's modules function");
  }
  std::set<std::string> names;
  for (const auto& m : plugin.modules) {
    if (m.name.empty() || !m.create || !m.params)
      throw InputError(path, 0, "plugin '" + plugin.name + "' adds a module without a name, create or params",
                       "build each ModuleInfo with MakeModuleInfo");
    if (!names.insert(m.name).second)
      throw InputError(path, 0, "plugin '" + plugin.name + "' adds module '" + m.name + "' twice",
                       "give each module its own name");
  }
  if (plugin.modules.empty())
    throw InputError(path, 0, "plugin '" + plugin.name + "' adds no module", "return at least one ModuleInfo");
  return plugin;
}

std::string ManifestJson(const LoadedPlugin& plugin, const std::string& file_name) {
  json modules = json::array();
  for (const auto& m : plugin.modules)
    modules.push_back(
        {{"name", m.name}, {"description", m.description}, {"needs", NeedsJson(m.needs)}, {"in_all", m.in_all}});
  const json doc = {{"slambox_plugin_manifest", 1},
                    {"api_version", SLAMBOX_API_VERSION},
                    {"plugin", plugin.name},
                    {"file", file_name},
                    {"modules", modules}};
  return doc.dump(1) + "\n";
}

std::vector<ManifestModule> ReadManifests(const std::string& dir) {
  std::vector<fs::path> files;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return {};
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.size() > 14 && name.ends_with(".manifest.json")) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  std::vector<ManifestModule> out;
  for (const auto& file : files) {
    const std::string where = file.string();
    const std::string fix = "rebuild slambox (the build writes it) or delete the stale manifest";
    json doc;
    try {
      std::ifstream in(file);
      doc = json::parse(in);
      if (doc.at("api_version").get<int>() != SLAMBOX_API_VERSION)
        throw InputError(where, 0,
                         "manifest of a plugin for API version " + std::to_string(doc.at("api_version").get<int>()) +
                             ", this slambox has " + std::to_string(SLAMBOX_API_VERSION),
                         fix);
      for (const auto& m : doc.at("modules")) {
        ManifestModule mm;
        mm.name = m.at("name").get<std::string>();
        mm.description = m.at("description").get<std::string>();
        const json& n = m.at("needs");
        mm.needs = {n.at("odometry").get<bool>(), n.at("lidar").get<bool>(), n.at("landmarks").get<bool>(),
                    n.at("map").get<bool>()};
        mm.in_all = m.at("in_all").get<bool>();
        mm.plugin_name = doc.at("plugin").get<std::string>();
        mm.plugin_path = (file.parent_path() / doc.at("file").get<std::string>()).string();
        out.push_back(std::move(mm));
      }
    } catch (const json::exception& e) {
      throw InputError(where, 0, std::string("malformed plugin manifest: ") + e.what(), fix);
    }
  }
  return out;
}

namespace {
std::string& LibraryDirOverride() {
  static std::string dir;
  return dir;
}
}  // namespace

void SetSlamboxLibraryDir(const std::string& dir) { LibraryDirOverride() = dir; }

std::string SlamboxLibraryDir() {
  if (!LibraryDirOverride().empty()) return LibraryDirOverride();
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return {};
  return (exe.parent_path().parent_path() / "lib" / "slambox").string();
}

std::string ShippedPluginDir() { return SlamboxLibraryDir() + "/plugins"; }

std::vector<std::string> PluginPathFiles(const std::string& value) {
  std::vector<std::string> out;
  std::stringstream in(value);
  std::string entry;
  while (std::getline(in, entry, ':')) {
    if (entry.empty()) continue;
    std::error_code ec;
    if (fs::is_directory(entry, ec)) {
      std::vector<std::string> found;
      for (const auto& e : fs::directory_iterator(entry, ec))
        if (e.path().extension() == ".so" && e.is_regular_file(ec)) found.push_back(e.path().string());
      std::sort(found.begin(), found.end());
      out.insert(out.end(), found.begin(), found.end());
    } else if (fs::exists(entry, ec)) {
      out.push_back(entry);
    } else {
      throw InputError("SLAMBOX_PLUGIN_PATH", 0, "'" + entry + "' does not exist",
                       "list plugin files or folders separated by ':' (or unset SLAMBOX_PLUGIN_PATH)");
    }
  }
  return out;
}

}  // namespace slambox
