// A plugin whose module takes a built-in's name: refused.
#include "core/plugin.hpp"
#include "slam/dead_reckoning.hpp"

namespace {
std::vector<slambox::ModuleInfo> Modules() { return {slambox::DeadReckoningModule()}; }  // "odometry"
}  // namespace

SLAMBOX_PLUGIN("clash-plugin", Modules)
