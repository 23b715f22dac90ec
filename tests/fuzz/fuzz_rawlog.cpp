// MRPT rawlogs (slam/mrpt/mrpt_rawlog, through MRPT's own deserialization), their content
// after gunzip: a converted log must assemble into a stream that survives the stream round
// trip, or be refused with an InputError naming the file.
//
// MRPT sizes a string or an array from its length field before it reads the elements, so a
// 3 kB input can ask for a 2.7 GB string (the harness's first finding): on a real machine
// that is a transient allocation followed by a clean "MRPT cannot read it" error, or a
// std::bad_alloc turned into one. Here allocations over 16 MiB fail with std::bad_alloc, as
// they would on a machine without the memory (no object of a <= 64 KiB input needs that
// much), so the fuzzer checks the reader's handling of that instead of stopping at
// libFuzzer's memory limits (README: "Hostile rawlogs").
#include <cstdint>
#include <cstdlib>
#include <new>
#include <string>
#include <vector>

#include "core/stream_io.hpp"
#include "datasets/laser_log.hpp"
#include "slam/mrpt/mrpt_rawlog.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace {
constexpr std::size_t kMaxAllocationBytes = std::size_t{16} << 20;  // inputs are <= 64 KiB: no real object needs more
bool capped = false;  ///< while the reader runs (libFuzzer's own buffers are larger)
void* Allocate(std::size_t n) {
  if (capped && n > kMaxAllocationBytes) throw std::bad_alloc();
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
}  // namespace

// libFuzzer's own malloc limit is lifted (LLVMFuzzerInitialize) so that a request refused
// here is not reported before it is refused. MRPT's aligned arrays (a scan's ranges) come
// from aligned_alloc, not operator new, and MRPT does not check it for null, so those stay
// unbounded: a scan whose length field asks for gigabytes ends this harness with libFuzzer's
// out-of-memory report (MRPT's limit, not slambox's: why scripts/fuzz.sh runs this harness
// only when named). Blocks may be allocated by the sanitizer runtime's operator new (inline
// code in libraries bound to it) and freed by this file's operator delete: the same malloc
// underneath, which ASan's new/delete pairing check would report.
extern "C" const char* __asan_default_options() { return "alloc_dealloc_mismatch=0"; }

extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
  static std::vector<char*> args;
  static char lift[] = "-malloc_limit_mb=2147483647";
  args.assign(*argv, *argv + *argc);
  args.insert(args.begin() + 1, lift);  // before the corpus folders; a later flag still wins
  args.push_back(nullptr);
  *argc += 1;
  *argv = args.data();
  return 0;
}

void* operator new(std::size_t n) { return Allocate(n); }
void* operator new[](std::size_t n) { return Allocate(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void* operator new(std::size_t n, std::align_val_t a) {
  if (capped && n > kMaxAllocationBytes) throw std::bad_alloc();
  const std::size_t align = static_cast<std::size_t>(a);
  if (void* p = std::aligned_alloc(align, (n + align - 1) / align * align + (n == 0 ? align : 0))) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n, std::align_val_t a) { return operator new(n, a); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace slambox;
  const std::string content(reinterpret_cast<const char*>(data), size);
  std::string bytes;
  fuzz::ExpectCleanResult(
      [&] {
        capped = true;
        struct Uncap {
          ~Uncap() { capped = false; }
        } uncap;
        bytes = SerializeStream(AssembleLaserLog(mrpt_bridge::ParseRawlog(content, "fuzz.rawlog"), "fuzz.rawlog", {}));
      },
      "fuzz.rawlog");
  if (bytes.empty()) return 0;
  try {
    if (SerializeStream(ParseStream(bytes, "roundtrip.stream")) != bytes) fuzz::Finding("rawlog stream round trip differs");
  } catch (const InputError& e) {
    fuzz::Finding(std::string("a converted rawlog does not read back: ") + e.what());
  }
  return 0;
}
