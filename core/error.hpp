#pragma once
// Bad user input (scenario, stream, graph, flag) is reported by throwing InputError.
// Its message names the file, the line (0 = unknown / whole file), what is wrong and the
// fix; the CLI prints it and exits non-zero. Bugs are asserts, not InputErrors.
#include <stdexcept>
#include <string>

namespace slambox {

class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, int line, const std::string& problem, const std::string& fix)
      : std::runtime_error(Format(file, line, problem, fix)), file_(file), line_(line) {}
  const std::string& file() const { return file_; }
  int line() const { return line_; }

 private:
  static std::string Format(const std::string& file, int line, const std::string& problem,
                            const std::string& fix) {
    std::string msg = file.empty() ? std::string("<input>") : file;
    if (line > 0) msg.append(":").append(std::to_string(line));
    msg.append(": ").append(problem);
    if (!fix.empty()) msg.append("\n  fix: ").append(fix);
    return msg;
  }
  std::string file_;
  int line_;
};

/// A module whose output is unusable (e.g. a non-finite pose from an `exec` child): the
/// run records `status: diverged` with this reason instead of `failed`.
class ModuleDiverged : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace slambox
