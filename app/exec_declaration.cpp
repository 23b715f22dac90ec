#include "app/exec_declaration.hpp"

#include <yaml-cpp/yaml.h>

#include <cstdlib>
#include <deque>
#include <filesystem>
#include <map>
#include <sstream>

#include "core/error.hpp"
#include "core/file_status.hpp"

namespace slambox {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

/// A parameter's value, bound to a ParamBinder so `--set` is parsed and checked the way
/// built-in modules' are.
struct ParamValue {
  double d = 0.0;
  int i = 0;
  bool b = false;
  int choice = 0;  ///< index into the string parameter's choices
};

}  // namespace

json BindExecParams(const ExecDeclaration& decl, const ParamOverrides* overrides, std::vector<ParamInfo>* list) {
  std::deque<ParamValue> values(decl.params.size());
  const auto bind_all = [&](ParamBinder& binder) {
    for (std::size_t k = 0; k < decl.params.size(); ++k) {
      const ExecParam& p = decl.params[k];
      ParamValue& v = values[k];
      if (p.type == ExecParamType::kDouble) binder.Bind(p.name, v.d, p.unit, p.meaning);
      else if (p.type == ExecParamType::kInt) binder.Bind(p.name, v.i, p.unit, p.meaning);
      else if (p.type == ExecParamType::kBool) binder.Bind(p.name, v.b, p.unit, p.meaning);
      else {
        EnumNames<int> names;  // a string parameter is an enum over its declared choices
        for (std::size_t c = 0; c < p.choices.size(); ++c) names.emplace_back(static_cast<int>(c), p.choices[c].c_str());
        binder.Bind(p.name, v.choice, names, p.meaning);
      }
    }
  };
  ParamBinder binder;
  bind_all(binder);
  ParamOverrides defaults;
  for (const ExecParam& p : decl.params) defaults[p.name] = p.default_text;
  binder.Apply(defaults, decl.name);  // the declared defaults, parsed and checked like --set values
  if (list) {  // bound again, now holding the defaults, so the listing shows them
    ParamBinder listing;
    bind_all(listing);
    *list = listing.List();
  }
  if (overrides) binder.Apply(*overrides, decl.name);
  json j = json::object();
  for (std::size_t k = 0; k < decl.params.size(); ++k) {
    const ExecParam& p = decl.params[k];
    const ParamValue& v = values[k];
    if (p.type == ExecParamType::kDouble) j[p.name] = v.d;
    else if (p.type == ExecParamType::kInt) j[p.name] = v.i;
    else if (p.type == ExecParamType::kBool) j[p.name] = v.b;
    else j[p.name] = p.choices[static_cast<std::size_t>(v.choice)];
  }
  return j;
}


namespace {

int Line(const YAML::Node& n) { return n.Mark().line + 1; }

constexpr const char* kNeedsFix = "use odometry, lidar, landmarks or map";

/// Sets the need named `name`; false for an unknown name.
bool AddNeed(const std::string& name, SensorNeeds& needs) {
  if (name == "odometry") needs.odometry = true;
  else if (name == "lidar") needs.lidar = true;
  else if (name == "landmarks") needs.landmarks = true;
  else if (name == "map") needs.map = true;
  else return false;
  return true;
}

}  // namespace

ExecDeclaration LoadExecDeclaration(const std::string& path) {
  const std::string fix = "see docs/exec_protocol.md, 'Declaring a module'";
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw InputError(path, 0, "cannot read the exec module declaration", "check the path (" + fix + ")");
  } catch (const YAML::Exception& e) {
    throw InputError(path, e.mark.line + 1, "not valid YAML: " + e.msg, fix);
  }
  if (!root.IsMap()) throw InputError(path, Line(root), "an exec declaration is a YAML map", fix);
  ExecDeclaration d;
  d.file = path;
  d.name = "exec:" + fs::path(path).stem().string();
  d.working_dir = fs::absolute(path).parent_path().string();
  d.needs = SensorNeeds{.odometry = false};
  const auto fail = [&](const YAML::Node& n, const std::string& problem, const std::string& how) -> void {
    throw InputError(path, Line(n), problem, how);
  };
  bool has_version = false, has_command = false;
  try {
    for (const auto& kv : root) {
      const std::string key = kv.first.as<std::string>();
      const YAML::Node& v = kv.second;
      if (key == "version") {
        if (v.as<int>() != 1) fail(v, "declaration version " + v.as<std::string>() + " is not supported", "write version: 1");
        has_version = true;
      } else if (key == "description") {
        d.description = v.as<std::string>();
      } else if (key == "command") {
        if (!v.IsSequence() || v.size() == 0) fail(v, "'command' must be a non-empty list (argv)", "write e.g. command: [/usr/bin/python3, module.py]");
        for (const auto& a : v) d.command.push_back(a.as<std::string>());
        has_command = true;
      } else if (key == "needs") {
        if (!v.IsSequence()) fail(v, "'needs' must be a list", "write e.g. needs: [odometry, lidar]");
        for (const auto& n : v) {
          const std::string s = n.as<std::string>();
          if (!AddNeed(s, d.needs)) fail(n, "unknown sensor need '" + s + "'", kNeedsFix);
        }
      } else if (key == "idle_timeout_s") {
        d.idle_timeout_s = v.as<double>();
        if (!(d.idle_timeout_s > 0)) fail(v, "'idle_timeout_s' must be positive", "write e.g. idle_timeout_s: 30");
      } else if (key == "baseline") {
        d.baseline = v.as<bool>();
      } else if (key == "params") {
        if (!v.IsMap()) fail(v, "'params' must be a map NAME: {type, default, ...}", fix);
        for (const auto& pkv : v) {
          ExecParam p;
          p.name = pkv.first.as<std::string>();
          const YAML::Node& pv = pkv.second;
          if (!pv.IsMap()) fail(pv, "parameter '" + p.name + "' must be a map {type, default, unit, meaning}", fix);
          bool has_default = false;
          std::string type;
          for (const auto& f : pv) {
            const std::string field = f.first.as<std::string>();
            if (field == "type") type = f.second.as<std::string>();
            else if (field == "default") p.default_text = f.second.as<std::string>(), has_default = true;
            else if (field == "unit") p.unit = f.second.as<std::string>();
            else if (field == "meaning") p.meaning = f.second.as<std::string>();
            else if (field == "choices") p.choices = f.second.as<std::vector<std::string>>();
            else fail(f.first, "unknown key '" + field + "' in parameter '" + p.name + "'", "use type, default, unit, meaning, choices");
          }
          const std::map<std::string, ExecParamType> types = {{"double", ExecParamType::kDouble},
                                                              {"int", ExecParamType::kInt},
                                                              {"bool", ExecParamType::kBool},
                                                              {"string", ExecParamType::kString}};
          if (!types.count(type))
            fail(pv, "parameter '" + p.name + "' has type '" + type + "'", "use type: double, int, bool or string");
          p.type = types.at(type);
          if (!has_default) fail(pv, "parameter '" + p.name + "' has no default", "add default: VALUE");
          if (p.type == ExecParamType::kString && p.choices.empty())
            fail(pv, "string parameter '" + p.name + "' has no choices", "add choices: [a, b] (typed options, not free text)");
          d.params.push_back(p);
        }
      } else {
        fail(kv.first, "unknown key '" + key + "'", "use version, description, command, needs, idle_timeout_s, baseline, params");
      }
    }
  } catch (const YAML::Exception& e) {
    throw InputError(path, e.mark.line + 1, "wrong value type: " + e.msg, fix);
  }
  if (!has_version) throw InputError(path, 1, "missing 'version'", "add version: 1");
  if (!has_command) throw InputError(path, 1, "missing 'command'", "add command: [PROGRAM, ARG...]");
  try {
    BindExecParams(d, nullptr, nullptr);  // defaults of the declared types
  } catch (const InputError& e) {
    throw InputError(path, 0, std::string("a parameter default does not fit its type: ") + e.what(), fix);
  }
  return d;
}


ExecDeclaration ParseInlineDeclaration(const std::string& argument) {
  const std::string where = "--exec " + argument;
  const std::string how = "write --exec NAME[:NEED,...]=COMMAND, e.g. --exec 'mine:odometry,lidar=python3 mine.py'";
  const auto eq = argument.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == argument.size())
    throw InputError(where, 0, "expected NAME[:NEED,...]=COMMAND", how);
  std::string name = argument.substr(0, eq), needs = "odometry";
  if (const auto colon = name.find(':'); colon != std::string::npos) {
    needs = name.substr(colon + 1);
    name = name.substr(0, colon);
  }
  if (name.empty() || name.find_first_of("/ ,") != std::string::npos)
    throw InputError(where, 0, "a module name without '/', ' ' or ','", how);
  ExecDeclaration d;
  d.name = "exec:" + name;
  d.file = "--exec " + name;
  d.description = "exec module from the command line: " + argument.substr(eq + 1);
  d.command = {"/bin/sh", "-c", argument.substr(eq + 1)};
  d.needs = SensorNeeds{.odometry = false};
  std::stringstream in(needs);
  for (std::string n; std::getline(in, n, ',');)
    if (!AddNeed(n, d.needs)) throw InputError(where, 0, "unknown sensor need '" + n + "'", kNeedsFix);
  return d;
}

std::vector<std::string> ExecPathFolders() {
  std::vector<std::string> folders;
  if (const char* env = std::getenv("SLAMBOX_EXEC_PATH")) {
    std::stringstream in(env);
    for (std::string f; std::getline(in, f, ':');)
      if (!f.empty()) folders.push_back(f);
  }
  return folders;
}


std::string FindExecDeclaration(const std::string& module_name) {
  const std::string spec = module_name.substr(5);  // after "exec:"
  if (spec.find('/') != std::string::npos || fs::path(spec).extension() == ".yaml") {
    if (!IsRegularFile(spec))
      throw InputError("--algo " + module_name, 0, "no exec declaration file '" + spec + "'",
                       "give the path of a NAME.yaml declaration (docs/exec_protocol.md)");
    return spec;
  }
  std::vector<std::string> folders = ExecPathFolders();
  folders.push_back(".");
  for (const auto& f : folders) {
    const fs::path p = fs::path(f) / (spec + ".yaml");
    if (IsRegularFile(p)) return p.string();
  }
  throw InputError("--algo " + module_name, 0, "no declaration " + spec + ".yaml in $SLAMBOX_EXEC_PATH or here",
                   "add its folder to SLAMBOX_EXEC_PATH, or write --algo exec:PATH/" + spec + ".yaml");
}


}  // namespace slambox
