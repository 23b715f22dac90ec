// CARMEN logs, plain text (datasets/carmen_log): the converted stream must survive the
// stream round trip.
#include <cstdint>
#include <string>

#include "core/stream_io.hpp"
#include "datasets/carmen_log.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace slambox;
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::string bytes;
  fuzz::ExpectCleanResult([&] { bytes = SerializeStream(ParseCarmenLog(text, "fuzz.log")); }, "fuzz.log");
  if (bytes.empty()) return 0;
  try {
    if (SerializeStream(ParseStream(bytes, "roundtrip.stream")) != bytes) fuzz::Finding("CARMEN stream round trip differs");
  } catch (const InputError& e) {
    fuzz::Finding(std::string("a converted CARMEN log does not read back: ") + e.what());
  }
  return 0;
}
