// TUM trajectories (core/tum): parsed poses are finite with increasing times.
#include <cmath>
#include <cstdint>
#include <string>

#include "core/tum.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace slambox;
  const std::string text(reinterpret_cast<const char*>(data), size);
  fuzz::ExpectCleanResult(
      [&] {
        const auto poses = ParseTum(text, "fuzz.tum");
        for (std::size_t i = 0; i < poses.size(); ++i) {
          const auto& p = poses[i];
          if (!std::isfinite(p.t_s) || !std::isfinite(p.pose.x) || !std::isfinite(p.pose.y) ||
              !std::isfinite(p.pose.theta))
            fuzz::Finding("non-finite TUM pose accepted");
          if (i > 0 && !(p.t_s > poses[i - 1].t_s)) fuzz::Finding("TUM times not increasing");
        }
      },
      "fuzz.tum");
  return 0;
}
