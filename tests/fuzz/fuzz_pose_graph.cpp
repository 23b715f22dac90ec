// g2o / TORO / iSAM pose(-landmark) graphs (slam/g2o_io): a parsed graph written as g2o must parse
// again and write the same text (the writer uses %.17g: doubles round-trip exactly).
#include <cstdint>
#include <string>

#include "slam/g2o_io.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace slambox;
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::string written;
  fuzz::ExpectCleanResult(
      [&] {
        const PoseGraphFile f = ParsePoseGraph(text, "fuzz.g2o");
        written = FormatPoseGraph(f.graph, f.vertex_ids, f.landmark_ids);
      },
      "fuzz.g2o");
  if (written.empty()) return 0;
  try {
    const PoseGraphFile g = ParsePoseGraph(written, "roundtrip.g2o");
    if (FormatPoseGraph(g.graph, g.vertex_ids, g.landmark_ids) != written) fuzz::Finding("pose graph round trip differs:\n" + written);
  } catch (const InputError& e) {
    fuzz::Finding(std::string("a written graph does not parse again: ") + e.what() + "\n" + written);
  }
  return 0;
}
