#include "app/registry.hpp"

#include <cstdlib>
#include <deque>
#include <filesystem>
#include <map>
#include <set>

#include "app/plugins.hpp"
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

namespace slambox {

namespace fs = std::filesystem;

namespace {

struct Registered {
  ModuleInfo info;
  std::string origin;  ///< empty: built-in
};

struct Registry {
  std::deque<Registered> modules;  // a deque: FindModule's references survive later loads
  std::vector<ManifestModule> shipped;             // declared by a manifest, plugin not loaded yet
  std::map<std::string, std::string> unavailable;  // shipped module -> why its plugin did not load
  std::vector<ManifestModule> failed;              // those modules, for listing
  std::set<std::string> loaded_files;              // canonical plugin paths
  bool environment_loaded = false;
};

Registry& State() {
  static Registry r = [] {
    Registry r;
    for (ModuleInfo m : {DeadReckoningModule(), EkfSlamModule(), GraphSlamModule(), FastSlam1Module(),
                         FastSlam2Module(), IcpOdometryModule(), IcpPoseSlamModule(), IcpLocalizationModule(),
                         MclModule()})
      r.modules.push_back({std::move(m), ""});
    r.shipped = ReadManifests(ShippedPluginDir());
    return r;
  }();
  if (!r.environment_loaded) {  // once, before the first lookup; a bad path is the command's error
    r.environment_loaded = true;
    if (const char* path = std::getenv("SLAMBOX_PLUGIN_PATH"))
      for (const auto& file : PluginPathFiles(path)) LoadPlugin(file);
  }
  return r;
}

const Registered* FindRegistered(const std::string& name) {
  for (const auto& m : State().modules)
    if (m.info.name == name) return &m;
  return nullptr;
}

// Name taken by a module other than those of `except_file` (a shipped plugin being loaded)?
std::string Owner(const std::string& name, const std::string& except_file) {
  if (const Registered* m = FindRegistered(name)) return m->origin.empty() ? "the built-in module" : m->origin;
  for (const auto& s : State().shipped)
    if (s.name == name && s.plugin_path != except_file) return "shipped plugin " + s.plugin_name;
  return "";
}

void LoadPluginFile(const std::string& path, const std::string& shipped_file) {
  Registry& r = State();
  std::error_code ec;
  const std::string canonical = fs::weakly_canonical(path, ec).string();
  if (r.loaded_files.count(canonical)) return;
  LoadedPlugin plugin = OpenPlugin(path);
  for (const auto& m : plugin.modules)
    if (const std::string owner = Owner(m.name, shipped_file); !owner.empty())
      throw InputError(path, 0, "plugin '" + plugin.name + "' adds module '" + m.name + "', a name " + owner + " has",
                       "rename the plugin's module (names are unique; see `slambox algorithms`)");
  r.loaded_files.insert(canonical);
  for (auto& m : plugin.modules) r.modules.push_back({std::move(m), "plugin " + plugin.name});
}

// Loads the shipped plugin in `file`; on failure its modules become unavailable, with the reason.
void LoadShipped(const std::string& file) {
  Registry& r = State();
  std::string reason;
  try {
    LoadPluginFile(file, file);
  } catch (const InputError& e) {  // the problem; the fix for a shipped plugin is FindModule's
    reason = e.what();
    reason = reason.substr(0, reason.find("\n  fix: "));
  }
  std::vector<ManifestModule> rest;
  for (auto& s : r.shipped) {
    if (s.plugin_path != file) {
      rest.push_back(std::move(s));
      continue;
    }
    if (reason.empty() && FindRegistered(s.name)) continue;
    r.unavailable[s.name] = reason.empty() ? "its plugin " + file + " no longer provides it" : reason;
    r.failed.push_back(std::move(s));
  }
  r.shipped = std::move(rest);
}

void LoadAllShipped() {
  while (!State().shipped.empty()) LoadShipped(State().shipped.front().plugin_path);
}

}  // namespace

void LoadPlugin(const std::string& path) { LoadPluginFile(path, ""); }

void RegisterModule(ModuleInfo module, const std::string& origin) {
  if (const std::string owner = Owner(module.name, ""); !owner.empty())
    throw InputError(origin, 0, "module '" + module.name + "' is a name " + owner + " has",
                     "rename the module (names are unique; see `slambox algorithms`)");
  State().modules.push_back({std::move(module), origin});
}

std::vector<ModuleInfo> AllModules() {
  LoadAllShipped();
  std::vector<ModuleInfo> out;
  for (const auto& m : State().modules) out.push_back(m.info);
  return out;
}

const ModuleInfo& FindModule(const std::string& name) {
  if (name.rfind("exec:", 0) == 0) return FindExecModule(name);  // a child process (docs/exec_protocol.md)
  if (const Registered* m = FindRegistered(name)) return m->info;
  for (const auto& s : State().shipped) {
    if (s.name != name) continue;
    LoadShipped(std::string(s.plugin_path));  // copy: LoadShipped rewrites the list
    if (const Registered* m = FindRegistered(name)) return m->info;
    break;
  }
  if (const auto it = State().unavailable.find(name); it != State().unavailable.end())
    throw InputError("--algo " + name, 0, "'" + name + "' is unavailable: its plugin does not load:\n  " + it->second,
                     "install what the plugin needs (scripts/setup.sh) and rebuild, or pick another algorithm");
  std::string names;
  for (const auto& m : ListModules())
    if (m.unavailable.empty()) names += (names.empty() ? "" : ", ") + m.name;
  throw InputError("--algo", 0, "unknown algorithm '" + name + "'", "use one of: " + names + ", all, or exec:NAME");
}

bool SensorsAllow(const ModuleInfo& module, const SensorSuite& sensors, bool has_map) {
  return (!module.needs.odometry || sensors.odometry) && (!module.needs.lidar || sensors.lidar) &&
         (!module.needs.landmarks || sensors.landmarks) && (!module.needs.map || has_map);
}

std::vector<ModuleListing> ListModules() {
  const Registry& r = State();
  std::vector<ModuleListing> out;
  for (const auto& m : r.modules)
    out.push_back({m.info.name, m.info.description, m.info.needs, m.origin, "", m.info.in_all});
  auto add = [&](const ManifestModule& s, std::string why) {
    std::error_code ec;
    if (why.empty() && !fs::is_regular_file(s.plugin_path, ec))
      why = "plugin file " + s.plugin_path + " not found (slambox was built or installed without it)";
    out.push_back({s.name, s.description, s.needs, "plugin " + s.plugin_name, why, s.in_all});
  };
  for (const auto& s : r.shipped) add(s, "");
  for (const auto& s : r.failed) add(s, r.unavailable.at(s.name));
  return out;
}

}  // namespace slambox
