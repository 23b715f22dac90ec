// Scenario YAML (sim/scenario_*) with `--set` overrides: leading lines "#set KEY=VALUE"
// (YAML comments) are passed as overrides. A loaded scenario is written back
// (ScenarioToYaml) and must load again to the same text; its size estimate is computed.
#include <cstdint>
#include <string>
#include <vector>

#include "sim/scenario.hpp"
#include "sim/scenario_limits.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace slambox;
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> sets;
  for (std::size_t pos = 0; text.compare(pos, 5, "#set ") == 0;) {
    const std::size_t end = text.find('\n', pos);
    sets.push_back(text.substr(pos + 5, end == std::string::npos ? std::string::npos : end - pos - 5));
    if (end == std::string::npos) break;
    pos = end + 1;
  }
  bool loaded = false;
  std::string yaml;
  fuzz::ExpectCleanResult(
      [&] {
        try {
          const Scenario s = LoadScenarioText(text, "fuzz.yaml", sets);
          yaml = ScenarioToYaml(s);
          (void)EstimateStreamSize(s);
          loaded = true;
        } catch (const InputError& e) {
          // An error about a --set value names that override, not the file.
          if (e.file().find("(--set ") != std::string::npos || e.file().rfind("--set", 0) == 0) return;
          throw;
        }
      },
      "fuzz.yaml");
  if (!loaded) return 0;
  try {
    const std::string again = ScenarioToYaml(LoadScenarioText(yaml, "roundtrip.yaml"));
    if (again != yaml) fuzz::Finding("scenario round trip differs:\n" + yaml + "\n---\n" + again);
  } catch (const InputError& e) {
    fuzz::Finding(std::string("a written scenario does not load again: ") + e.what() + "\n" + yaml);
  }
  return 0;
}
