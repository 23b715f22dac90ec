#pragma once
// Test support: run the `slambox` binary with arguments, capturing its exit code and
// stdout + stderr (through a per-process temporary file).
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

namespace slambox::testing {

struct CliResult {
  int code = -1;       ///< exit status (-1: killed by a signal)
  std::string output;  ///< stdout + stderr
};

inline CliResult RunSlambox(const std::string& binary, const std::string& args) {
  const std::string log =
      (std::filesystem::temp_directory_path() / ("slambox_cli_log_" + std::to_string(getpid()))).string();
  const int status = std::system((binary + " " + args + " > " + log + " 2>&1").c_str());
  std::ifstream in(log);
  std::stringstream s;
  s << in.rdbuf();
  std::filesystem::remove(log);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, s.str()};
}

/// Folders handed out by FreshTempDir, removed when the test process exits normally.
struct TempDirRegistry {
  std::vector<std::filesystem::path> dirs;
  ~TempDirRegistry() {
    std::error_code ignored;
    for (const auto& d : dirs) std::filesystem::remove_all(d, ignored);
  }
};

/// An empty folder slambox_<tag>_<pid> under the system's temporary folder, removed with
/// everything in it when the test process exits.
inline std::filesystem::path FreshTempDir(const std::string& tag) {
  static TempDirRegistry registry;
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("slambox_" + tag + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  registry.dirs.push_back(dir);
  return dir;
}

/// A whole file's text ("" when it cannot be read).
inline std::string ReadText(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace slambox::testing
