#pragma once
// Questions about a path that never throw. std::filesystem's plain overloads throw
// filesystem_error when the name is longer than the system allows (ENAMETOOLONG, found by
// fuzz_sweep with a 1 kB scenario name), for a loop of symbolic links or a folder without
// permission. A path read from a file or the command line is untrusted: for it the answer
// is "no", and the caller's InputError names the file, the line and the fix.
#include <filesystem>
#include <system_error>

namespace slambox {

inline bool IsRegularFile(const std::filesystem::path& p) {
  std::error_code ec;
  return std::filesystem::is_regular_file(p, ec);
}
inline bool PathExists(const std::filesystem::path& p) {
  std::error_code ec;
  return std::filesystem::exists(p, ec);
}
/// Both name one existing file (hard links, `./a` and `a`); false if either is missing.
inline bool SameFile(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code ec;
  return std::filesystem::equivalent(a, b, ec);
}

}  // namespace slambox
