#pragma once
// The declaration of an `exec` module (docs/exec_protocol.md, "Declaring a module"): a
// small YAML file with the command, the sensors it needs and its typed parameters.
#include <nlohmann/json.hpp>
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
  bool baseline = false;  ///< `baseline: true`: a reference, not a method (ModuleInfo::baseline)
  std::vector<ExecParam> params;
};

/// Parses a declaration file; throws InputError with the file, line and fix.
ExecDeclaration LoadExecDeclaration(const std::string& path);
/// A declaration on the command line, `--exec NAME[:NEED,...]=COMMAND`: COMMAND runs with
/// /bin/sh -c in the current folder; needs default to odometry; no parameters. Throws
/// InputError naming the argument.
ExecDeclaration ParseInlineDeclaration(const std::string& argument);
/// The folders of $SLAMBOX_EXEC_PATH (`:`-separated), in order.
std::vector<std::string> ExecPathFolders();
/// The declaration file of `exec:NAME` (NAME.yaml in $SLAMBOX_EXEC_PATH's folders, then
/// the current folder) or `exec:PATH.yaml`; throws InputError when there is none.
std::string FindExecDeclaration(const std::string& module_name);
/// The parameters as the header's `params` object: the declared defaults, then
/// `overrides` (from `--set algo.exec:NAME.FIELD`), parsed and checked by ParamBinder
/// (InputError on a bad value or an unknown field). `list` (optional) gets the listing.
nlohmann::json BindExecParams(const ExecDeclaration& declaration, const ParamOverrides* overrides,
                              std::vector<ParamInfo>* list);

}  // namespace slambox
