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

}  // namespace slambox::testing
