#pragma once
// Binds IcpConfig's fields for `--set algo.NAME.FIELD=VALUE`: the enums through their
// name tables, the numbers with their allowed ranges (checked once, by the binder, when
// the module is built).
#include <string>

#include "core/params.hpp"
#include "slam/icp.hpp"

namespace slambox {

const EnumNames<IcpMetric>& IcpMetricNames();
const EnumNames<IcpCorrespondence>& IcpCorrespondenceNames();
const EnumNames<IcpRobustKernel>& IcpRobustKernelNames();

/// Binds every IcpConfig field, names prefixed with `prefix` (e.g. "" or "loop_icp_").
void BindIcpParams(IcpConfig& icp, ParamBinder& b, const std::string& prefix = "");

}  // namespace slambox
