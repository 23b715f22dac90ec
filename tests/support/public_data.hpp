#pragma once
// Test and benchmark support: where the public datasets live. $SLAMBOX_DATA wins; else
// ../shared/data beside the project (also from a worktree two levels down).
#include <cstdlib>
#include <filesystem>
#include <string>

namespace slambox::testing {

/// The data folder's path, or "" when none exists. `source_dir` is the repository root.
inline std::string PublicDataDir(const std::string& source_dir) {
  if (const char* env = std::getenv("SLAMBOX_DATA"); env != nullptr && *env != '\0')
    return std::filesystem::is_directory(env) ? std::string(env) : std::string();
  for (const char* rel : {"/../shared/data", "/../../shared/data"}) {
    const std::filesystem::path p = std::filesystem::path(source_dir + rel);
    if (std::filesystem::is_directory(p)) return std::filesystem::weakly_canonical(p).string();
  }
  return {};
}

/// Path of `relative` inside the data folder, or "" when it is absent.
inline std::string PublicDataFile(const std::string& source_dir, const std::string& relative) {
  const std::string dir = PublicDataDir(source_dir);
  if (dir.empty()) return {};
  const std::string path = dir + "/" + relative;
  return std::filesystem::exists(path) ? path : std::string();
}

}  // namespace slambox::testing
