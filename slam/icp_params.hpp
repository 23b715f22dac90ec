#pragma once
// Binds IcpConfig's fields for `--set algo.NAME.FIELD=VALUE`. Enum fields are bound
// through their names (IcpChoices) and resolved once when the module is built.
#include <string>

#include "core/params.hpp"
#include "slam/icp.hpp"

namespace slambox {

struct IcpChoices {
  std::string metric = "point-to-line";    ///< point-to-point | point-to-line
  std::string correspondence = "projection";  ///< kdtree | projection
  std::string robust_kernel = "none";     ///< none | huber | geman-mcclure
};

/// Binds every IcpConfig field, names prefixed with `prefix` (e.g. "" or "loop_").
void BindIcpParams(IcpConfig& icp, IcpChoices& choices, ParamBinder& b, const std::string& prefix = "");
/// IcpConfig with the enums set from `choices`; throws InputError for invalid values.
IcpConfig ResolveIcpConfig(IcpConfig icp, const IcpChoices& choices, const std::string& module);

}  // namespace slambox
