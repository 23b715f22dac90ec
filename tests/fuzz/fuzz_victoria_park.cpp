// Victoria Park text (datasets/victoria_park): the converted stream must survive the
// stream round trip.
#include <cstdint>
#include <string>

#include "core/stream_io.hpp"
#include "datasets/victoria_park.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace slambox;
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::string bytes;
  fuzz::ExpectCleanResult([&] { bytes = SerializeStream(ParseVictoriaPark(text, "fuzz.txt")); }, "fuzz.txt");
  if (bytes.empty()) return 0;
  try {
    if (SerializeStream(ParseStream(bytes, "roundtrip.stream")) != bytes) fuzz::Finding("Victoria Park round trip differs");
  } catch (const InputError& e) {
    fuzz::Finding(std::string("a converted Victoria Park file does not read back: ") + e.what());
  }
  return 0;
}
