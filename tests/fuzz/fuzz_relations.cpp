// Relation files (eval/relations): every parsed relation is finite, has a positive line
// number, and the parsed set scores against a trajectory without throwing.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "eval/relations.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace slambox;
  const std::string text(reinterpret_cast<const char*>(data), size);
  fuzz::ExpectCleanResult(
      [&] {
        const auto relations = ParseRelations(text, "fuzz.relations");
        for (const auto& r : relations) {
          if (!std::isfinite(r.t_i_s) || !std::isfinite(r.t_j_s) || !std::isfinite(r.T_i_j.x) ||
              !std::isfinite(r.T_i_j.y) || !std::isfinite(r.T_i_j.theta))
            fuzz::Finding("non-finite relation accepted");
          if (r.line <= 0) fuzz::Finding("relation without its line number");
        }
        // Scoring is total: a short straight trajectory, every relation matched or counted
        // unmatched, every error finite.
        std::vector<StampedPose> trajectory;
        for (int k = 0; k <= 10; ++k) trajectory.push_back({0.1 * k, SE2{0.1 * k, 0.0, 0.01 * k}});
        const auto errors = ComputeRelationErrors(relations, trajectory);
        if (errors.translation_m.size() + static_cast<std::size_t>(errors.unmatched) != relations.size())
          fuzz::Finding("relations neither matched nor counted unmatched");
        for (double e : errors.translation_m)
          if (!std::isfinite(e) || e < 0) fuzz::Finding("relation error not finite");
        for (double e : errors.rotation_deg)
          if (!std::isfinite(e) || e < 0 || e > 180.0 + 1e-9) fuzz::Finding("relation rotation outside [0, 180] deg");
      },
      "fuzz.relations");
  return 0;
}
