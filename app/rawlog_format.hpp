#pragma once
// MRPT rawlogs through the shipped MRPT plugin (slam/mrpt/mrpt_rawlog.hpp): the slambox
// executable links no MRPT, so `convert rawlog` and `export --format rawlog` load
// lib/slambox/plugins/slambox-mrpt.so and call its slambox_rawlog_format entry.
#include "core/laser_log.hpp"

namespace slambox {

/// Throws InputError with the fix when the plugin is missing, not loadable, has no rawlog
/// entry or is from another SLAMBOX_API_VERSION.
const LogFormatEntry& RawlogFormat();

}  // namespace slambox
