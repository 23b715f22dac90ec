#pragma once
// `exec` modules: a SLAM module that is a child process speaking the JSON Lines protocol
// of docs/exec_protocol.md, declared by a small YAML file and named `exec:NAME`.
#include <string>
#include <vector>

#include "core/slam_module.hpp"

namespace slambox {

enum class ExecParamType { kDouble, kInt, kBool, kString };

struct ExecParam {
  std::string name;
  ExecParamType type = ExecParamType::kDouble;
  std::string default_text;
  std::string unit;
  std::string meaning;
  std::vector<std::string> choices;  ///< strings only
};

struct ExecDeclaration {
  std::string name;  ///< "exec:" + the file's stem
  std::string file;
  std::string description;
  std::vector<std::string> command;  ///< argv, run in working_dir
  std::string working_dir;           ///< the declaration file's folder
  SensorNeeds needs;
  double idle_timeout_s = 30.0;  ///< [s] child killed after this long without progress
  std::vector<ExecParam> params;
};

/// Parses a declaration file; throws InputError with the file, line and fix.
ExecDeclaration LoadExecDeclaration(const std::string& path);
/// The declaration file of `exec:NAME` (NAME.yaml in $SLAMBOX_EXEC_PATH's folders, then
/// the current folder) or `exec:PATH.yaml`; throws InputError when there is none.
std::string FindExecDeclaration(const std::string& module_name);
ModuleInfo ExecModuleInfo(const ExecDeclaration& declaration);
/// Every declaration in $SLAMBOX_EXEC_PATH's folders (for `slambox algorithms`), by name;
/// a file that does not load is left out.
std::vector<const ModuleInfo*> ExecModulesOnPath();
/// The registry's resolver for `exec:` names: loads each declaration once and keeps it,
/// under its canonical name and the name it was asked by.
const ModuleInfo& FindExecModule(const std::string& module_name);

}  // namespace slambox
