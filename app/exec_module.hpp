#pragma once
// `exec` modules: a SLAM module that is a child process speaking the JSON Lines protocol
// of docs/exec_protocol.md, declared by a small YAML file and named `exec:NAME`.
#include <string>
#include <vector>

#include "app/exec_declaration.hpp"
#include "core/slam_module.hpp"

namespace slambox {

ModuleInfo ExecModuleInfo(const ExecDeclaration& declaration);
/// Every declaration in $SLAMBOX_EXEC_PATH's folders (for `slambox algorithms`), by name;
/// a file that does not load is left out.
std::vector<const ModuleInfo*> ExecModulesOnPath();
/// The registry's resolver for `exec:` names: loads each declaration once and keeps it,
/// under its canonical name and the name it was asked by.
const ModuleInfo& FindExecModule(const std::string& module_name);
/// Makes a declaration from the command line (`--exec`) findable as its name.
void DeclareExecModule(const ExecDeclaration& declaration);

}  // namespace slambox
