// `slambox exec-check NAME|FILE.yaml`: the conformance test of the exec protocol
// (docs/exec_protocol.md, "Conformance") that any implementation can run.
#include <algorithm>
#include <iostream>
#include <memory>

#include "app/commands.hpp"
#include "app/registry.hpp"
#include "core/error.hpp"
#include "core/json_io.hpp"
#include "sim/scenario.hpp"
#include "sim/simulate.hpp"

namespace slambox {

namespace {

struct CheckRequest {
  std::string module;
  std::vector<std::string> sets;
};

/// The canned stream: `loop`, seed 0, 30 s, with a gyro beside odometry and LIDAR.
Stream CannedStream() {
  return Simulate(LoadScenario("loop", {"duration_s=30", "sensors.gyro.rate_hz=50"}), 0);
}

int Check(const CheckRequest& r) {
  const std::string name = r.module.rfind("exec:", 0) == 0 ? r.module : "exec:" + r.module;
  const ModuleInfo& info = FindModule(name);
  const Stream stream = CannedStream();
  ParamOverrides overrides;
  for (const auto& s : r.sets) {
    const auto eq = s.find('=');
    if (eq == std::string::npos) throw InputError("--set " + s, 0, "expected FIELD=VALUE", "write e.g. --set noise_scale=2");
    overrides[s.substr(0, eq)] = s.substr(eq + 1);
  }
  int failures = 0;
  const auto report = [&](bool ok, const std::string& what) {
    std::cout << (ok ? "ok   " : "FAIL ") << what << "\n";
    failures += !ok;
    return ok;
  };
  std::vector<double> times = {0.0};
  for (const auto& e : stream.events) times.push_back(EventTime(e));
  std::vector<nlohmann::json> runs;
  for (int run = 0; run < 2; ++run) {
    Estimate estimate;
    try {
      const auto module = info.create(overrides);
      estimate = Replay(*module, stream);
    } catch (const std::exception& e) {
      report(false, "run " + std::to_string(run + 1) + ": the protocol is followed to done and exit 0: " + e.what());
      return 1;
    }
    report(true, "run " + std::to_string(run + 1) + ": " + std::to_string(stream.events.size()) +
                     " events in, valid answers, done, exit status 0");
    const auto& tr = estimate.trajectory;
    if (run == 0) {
      report(!tr.empty(), "the trajectory has poses (" + std::to_string(tr.size()) + ")");
      const auto off = std::find_if(tr.begin(), tr.end(), [&](const PoseEstimate& p) {
        return !std::binary_search(times.begin(), times.end(), p.t_s);
      });
      report(off == tr.end(), off == tr.end() ? "every pose time is 0 or an event time"
                                              : "a pose time is neither 0 nor an event time: " + std::to_string(off->t_s));
    }
    estimate.step_time_s.clear();
    estimate.finish_time_s = 0.0;
    runs.push_back(ToJson(estimate));
  }
  report(runs[0] == runs[1], "two runs give identical answers (deterministic)");
  std::cout << (failures ? "exec-check: " + std::to_string(failures) + " check(s) failed\n" : "exec-check: conforms\n");
  return failures ? 1 : 0;
}

}  // namespace

void AddExecCheckCommand(CLI::App& app) {
  auto request = std::make_shared<CheckRequest>();
  auto* cmd = app.add_subcommand("exec-check", "conformance test of an exec module (docs/exec_protocol.md)");
  cmd->add_option("module", request->module, "exec:NAME, NAME, or a declaration FILE.yaml")->required();
  cmd->add_option("--set", request->sets, "module parameter FIELD=VALUE");
  cmd->callback([request] {
    if (const int code = Check(*request)) throw CommandExit{code};
  });
}

}  // namespace slambox
