// A module plugin for the tests: `test-odometry` (the built-in dead reckoning under another
// name), `test-fault`, which crashes (abort) or hangs on streams with an odd seed, so a
// sweep shows both kinds of run, and `test-named-only` (dead reckoning again, with
// ModuleInfo::in_all = false: run only when named, never by `all`).
#include <chrono>
#include <cstdlib>
#include <thread>

#include "core/plugin.hpp"
#include "slam/dead_reckoning.hpp"

namespace {

using namespace slambox;

enum class FaultKind { kCrash, kHang, kThrow };

struct FaultConfig {
  FaultKind fault = FaultKind::kCrash;  ///< what happens on an odd seed
};

void BindParams(FaultConfig& c, ParamBinder& b) {
  static const EnumNames<FaultKind> names = {{FaultKind::kCrash, "crash"}, {FaultKind::kHang, "hang"},
                                             {FaultKind::kThrow, "throw"}};
  b.Bind("fault", c.fault, names, "what the module does on a stream with an odd seed");
}

class Fault : public SlamModule {
 public:
  explicit Fault(const FaultConfig& c) : config_(c) {}
  void Start(const StreamHeader& header) override {
    if (header.seed % 2 == 0) return;
    if (config_.fault == FaultKind::kCrash) std::abort();
    if (config_.fault == FaultKind::kThrow) throw std::runtime_error("test-fault throws on odd seeds");
    for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
  }
  Estimate Finish() override { return {}; }

 private:
  FaultConfig config_;
};

std::vector<ModuleInfo> Modules() {
  ModuleInfo odometry = DeadReckoningModule();
  odometry.name = "test-odometry";
  ModuleInfo named_only = DeadReckoningModule();
  named_only.name = "test-named-only";
  named_only.in_all = false;
  return {odometry,
          MakeModuleInfo<Fault, FaultConfig>("test-fault", "crashes or hangs on odd seeds (tests)", {.odometry = true},
                                             &BindParams),
          named_only};
}

}  // namespace

SLAMBOX_PLUGIN("test-plugin", Modules)
