#pragma once
// The one interface where modules are interchangeable: a SLAM module consumes stream
// events in time order and yields an Estimate. Modules are found by name in the
// registry (app/registry.cpp) through a ModuleInfo.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/estimate.hpp"
#include "core/params.hpp"
#include "core/stream.hpp"

namespace slambox {

class SlamModule {
 public:
  virtual ~SlamModule() = default;
  /// Called once before any event: sensor configurations (noise models), start pose.
  virtual void Start(const StreamHeader& header) = 0;
  virtual void OnOdometry(const OdometryEvent&) {}
  virtual void OnLaserScan(const LaserScanEvent&) {}
  virtual void OnLandmarks(const LandmarkEvent&) {}
  virtual void OnGyro(const GyroEvent&) {}
  /// Called once after the last event; smoothers run their final optimization here.
  virtual Estimate Finish() = 0;
};

struct SensorNeeds {
  bool odometry = true;
  bool lidar = false;
  bool landmarks = false;
  bool map = false;  ///< a known map: the stream's world has walls (localization; real logs have none)
};

struct ModuleInfo {
  std::string name;         ///< e.g. "ekf-slam"
  std::string description;  ///< one line for `slambox algorithms`
  SensorNeeds needs;
  /// Parameters with their defaults (for `--params`).
  std::function<std::vector<ParamInfo>()> params;
  /// Builds the module with `--set algo.NAME.*` overrides applied; throws InputError.
  std::function<std::unique_ptr<SlamModule>(const ParamOverrides&)> create;
  /// A reference to compare against, not a method being judged (dead reckoning): written
  /// to metrics.json's `modules` and sweep.json, and drawn orange and dashed.
  bool baseline = false;
  /// Run by `--algo all` (and a sweep's `algorithms: [all]`) when the sensors allow it.
  /// Expensive peers are run only when named: false keeps them out of `all` (mrpt-graphslam,
  /// minutes to hours per stream); `slambox algorithms` says "named only, not in all".
  bool in_all = true;
};

/// ModuleInfo for a module `Module(const Config&)` whose fields `bind` names.
template <class Module, class Config>
ModuleInfo MakeModuleInfo(std::string name, std::string description, SensorNeeds needs,
                          void (*bind)(Config&, ParamBinder&)) {
  ModuleInfo info;
  info.name = name;
  info.description = std::move(description);
  info.needs = needs;
  info.params = [bind] {
    Config c;
    ParamBinder b;
    bind(c, b);
    return b.List();
  };
  info.create = [bind, name](const ParamOverrides& overrides) -> std::unique_ptr<SlamModule> {
    Config c;
    ParamBinder b;
    bind(c, b);
    b.Apply(overrides, name);
    b.Validate(name);  // every bound number in its range, once (Ceres' Options::IsValid)
    return std::make_unique<Module>(c);
  };
  return info;
}

/// Feeds every event of `stream` to `module` in order, timing each call, and returns the
/// module's Estimate with step_time_s and finish_time_s filled in.
Estimate Replay(SlamModule& module, const Stream& stream);

}  // namespace slambox
