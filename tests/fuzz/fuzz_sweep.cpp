// Sweep YAML (app/sweep_spec): ParseSweepSpec, then the runs are expanded (when there
// are at most 10000: a big sweep is valid, expanding it is only slow) with distinct ids
// for distinct (scenario, sets, seed).
#include <cstdint>
#include <string>

#include "app/sweep_spec.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace slambox;
  const std::string text(reinterpret_cast<const char*>(data), size);
  fuzz::ExpectCleanResult(
      [&] {
        const SweepSpec spec = ParseSweepSpec(text, "fuzz-sweep.yaml");
        double runs = static_cast<double>(spec.scenarios.size() * spec.seeds.size());
        for (const auto& [key, values] : spec.grid) runs *= static_cast<double>(values.size());
        if (runs > 10000) return;
        if (ExpandSweep(spec).size() != static_cast<std::size_t>(runs)) fuzz::Finding("ExpandSweep run count");
      },
      "fuzz-sweep.yaml");
  return 0;
}
