#pragma once
// JSON forms of the plain result types, so a run folder can be re-read by `slambox
// report` and drawn without re-running anything. Non-finite numbers become null.
#include <nlohmann/json.hpp>
#include <string>

#include "core/estimate.hpp"
#include "core/stream.hpp"
#include "core/world.hpp"

namespace slambox {

/// Parses a JSON file; InputError with the file, the line and the parser's message.
nlohmann::json ReadJsonFile(const std::string& path);

nlohmann::json ToJson(const SE2& pose);          ///< [x, y, theta_rad]
SE2 SE2FromJson(const nlohmann::json& j);
nlohmann::json ToJson(const World& world);
World WorldFromJson(const nlohmann::json& j);
nlohmann::json ToJson(const Estimate& estimate);
Estimate EstimateFromJson(const nlohmann::json& j);
nlohmann::json ToJson(const SensorSuite& sensors);
/// Inverse of ToJson(SensorSuite); a missing key keeps the config struct's default.
SensorSuite SensorSuiteFromJson(const nlohmann::json& j);

}  // namespace slambox
