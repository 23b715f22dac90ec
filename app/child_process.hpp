#pragma once
// A child process with its stdin, stdout and stderr on non-blocking pipes, for `exec`
// modules. One poll() loop moves bytes both ways, so neither a child that writes a lot
// of stderr nor one that answers while it reads can deadlock against slambox; a child
// that makes no progress for idle_timeout_s is killed (its whole process group).
// Starting a child sets SIGPIPE to ignored in slambox (a write to a child that exited
// must fail with EPIPE, not kill slambox); the child gets the default disposition back.
#include <sys/types.h>

#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace slambox {

struct ChildCommand {
  std::vector<std::string> argv;  ///< argv[0] is looked up in PATH
  std::string working_dir;        ///< empty: slambox's own
  double idle_timeout_s = 30.0;   ///< [s] without a byte read or written
};

/// The child did something that ends it: exited early, timed out, could not start.
class ChildError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ChildProcess {
 public:
  using LineHandler = std::function<void(std::string_view line)>;

  /// Starts the child; throws ChildError when the command cannot be executed.
  explicit ChildProcess(const ChildCommand& command);
  ~ChildProcess();  ///< kills the child if it still runs
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  /// Writes `data` to the child's stdin, handing every complete stdout line (without
  /// '\n') to `on_line` meanwhile. Throws ChildError when the child closed its stdin
  /// (exited) or timed out; exceptions of `on_line` propagate.
  void Write(std::string_view data, const LineHandler& on_line);
  /// Closes stdin, reads stdout to its end and waits for the exit. Returns the exit
  /// status as text ("" for status 0, else "exit status 3" / "killed by signal 11").
  std::string CloseAndWait(const LineHandler& on_line);
  void Kill();
  /// The last ~1 KiB of the child's stderr.
  std::string StderrTail() const;
  long stdout_lines() const { return lines_; }

 private:
  /// One poll round; returns false when nothing could move within the idle timeout.
  bool Pump(std::string_view& pending, const LineHandler& on_line);
  void ReadStdout(const LineHandler& on_line);
  void ReadStderr();
  std::string WaitForExit();

  pid_t pid_ = -1;
  int stdin_ = -1, stdout_ = -1, stderr_ = -1;
  double idle_timeout_s_ = 30.0;
  std::string partial_line_;
  std::string stderr_tail_;
  long lines_ = 0;
};

}  // namespace slambox
