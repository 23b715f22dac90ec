// Stream files (core/stream_io): ParseStream, then the round trip serialize -> parse ->
// serialize gives the same bytes.
#include <cstdint>
#include <string>

#include "core/stream_io.hpp"
#include "tests/fuzz/fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace slambox;
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  fuzz::ExpectCleanResult(
      [&] {
        const Stream s = ParseStream(bytes, "fuzz.stream");
        const std::string again = SerializeStream(s);
        if (SerializeStream(ParseStream(again, "roundtrip.stream")) != again) fuzz::Finding("stream round trip differs");
      },
      "fuzz.stream");
  return 0;
}
