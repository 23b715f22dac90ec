#include "app/child_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <sstream>
#include <thread>

namespace slambox {

namespace {

constexpr std::size_t kStderrKeep = 1024;
constexpr std::size_t kMaxLineBytes = 64u << 20;  // a longer stdout line is garbage, not an answer

std::string Seconds(double s) {
  std::ostringstream out;
  out << s << " s";
  return out.str();
}

void CloseFd(int& fd) {
  if (fd >= 0) close(fd);
  fd = -1;
}

void SetNonBlocking(int fd) { fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK); }

}  // namespace

ChildProcess::ChildProcess(const ChildCommand& command) : idle_timeout_s_(command.idle_timeout_s) {
  if (command.argv.empty()) throw ChildError("empty command");
  // Writing to a child that has exited must give EPIPE, not kill slambox.
  signal(SIGPIPE, SIG_IGN);
  int in[2], out[2], err[2], status[2];
  if (pipe2(in, O_CLOEXEC) || pipe2(out, O_CLOEXEC) || pipe2(err, O_CLOEXEC) || pipe2(status, O_CLOEXEC))
    throw ChildError(std::string("pipe: ") + std::strerror(errno));
  std::vector<char*> argv;
  for (const auto& a : command.argv) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const pid_t parent = getpid();
  pid_ = fork();
  if (pid_ < 0) throw ChildError(std::string("fork: ") + std::strerror(errno));
  if (pid_ == 0) {
    // Child: only async-signal-safe calls until exec.
    setpgid(0, 0);
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(127);
    signal(SIGPIPE, SIG_DFL);
    dup2(in[0], 0), dup2(out[1], 1), dup2(err[1], 2);
    int e = 0;
    if (!command.working_dir.empty() && chdir(command.working_dir.c_str()) != 0) e = errno;
    if (e == 0) {
      execvp(argv[0], argv.data());
      e = errno;
    }
    [[maybe_unused]] const ssize_t n = write(status[1], &e, sizeof e);
    _exit(127);
  }
  setpgid(pid_, pid_);  // also from the parent, so Kill() reaches the group at once
  close(in[0]), close(out[1]), close(err[1]), close(status[1]);
  stdin_ = in[1], stdout_ = out[0], stderr_ = err[0];
  int e = 0;
  const ssize_t n = read(status[0], &e, sizeof e);  // EOF (0 bytes) once exec succeeded
  close(status[0]);
  if (n == sizeof e) {
    waitpid(pid_, nullptr, 0);
    pid_ = -1;
    CloseFd(stdin_), CloseFd(stdout_), CloseFd(stderr_);
    throw ChildError("cannot start '" + command.argv[0] + "'" +
                     (command.working_dir.empty() ? "" : " in " + command.working_dir) + ": " + std::strerror(e));
  }
  SetNonBlocking(stdin_), SetNonBlocking(stdout_), SetNonBlocking(stderr_);
}

ChildProcess::~ChildProcess() {
  Kill();
  CloseFd(stdin_), CloseFd(stdout_), CloseFd(stderr_);
}

void ChildProcess::Kill() {
  if (pid_ <= 0) return;
  if (stderr_ >= 0) ReadStderr();  // what it said before it is killed (non-blocking)
  kill(-pid_, SIGKILL);
  waitpid(pid_, nullptr, 0);
  pid_ = -1;
}

std::string ChildProcess::StderrTail() const { return stderr_tail_; }

void ChildProcess::ReadStderr() {
  char buf[65536];
  for (;;) {
    const ssize_t n = read(stderr_, buf, sizeof buf);
    if (n > 0) {
      stderr_tail_.append(buf, static_cast<std::size_t>(n));
      if (stderr_tail_.size() > 2 * kStderrKeep) stderr_tail_.erase(0, stderr_tail_.size() - kStderrKeep);
      continue;
    }
    if (n == 0) CloseFd(stderr_);
    return;  // EOF or EAGAIN
  }
}

void ChildProcess::ReadStdout(const LineHandler& on_line) {
  char buf[65536];
  for (;;) {
    const ssize_t n = read(stdout_, buf, sizeof buf);
    if (n <= 0) {
      if (n == 0) CloseFd(stdout_);
      return;
    }
    std::string_view chunk(buf, static_cast<std::size_t>(n));
    for (std::size_t nl = chunk.find('\n'); nl != std::string_view::npos; nl = chunk.find('\n')) {
      ++lines_;
      if (partial_line_.empty()) {
        on_line(chunk.substr(0, nl));
      } else {
        partial_line_.append(chunk.substr(0, nl));
        const std::string line = std::move(partial_line_);
        partial_line_.clear();
        on_line(line);
      }
      chunk.remove_prefix(nl + 1);
    }
    partial_line_.append(chunk);
    if (partial_line_.size() > kMaxLineBytes)
      throw ChildError("stdout line " + std::to_string(lines_ + 1) + " is longer than 64 MiB");
  }
}

bool ChildProcess::Pump(std::string_view& pending, const LineHandler& on_line) {
  pollfd fds[3];
  int n = 0;
  const int in_at = !pending.empty() && stdin_ >= 0 ? n++ : -1;
  if (in_at >= 0) fds[in_at] = {stdin_, POLLOUT, 0};
  const int out_at = stdout_ >= 0 ? n++ : -1;
  if (out_at >= 0) fds[out_at] = {stdout_, POLLIN, 0};
  const int err_at = stderr_ >= 0 ? n++ : -1;
  if (err_at >= 0) fds[err_at] = {stderr_, POLLIN, 0};
  if (n == 0) return true;
  int ready;
  do ready = poll(fds, static_cast<nfds_t>(n), static_cast<int>(idle_timeout_s_ * 1000.0));
  while (ready < 0 && errno == EINTR);
  if (ready == 0) return false;
  if (err_at >= 0 && fds[err_at].revents) ReadStderr();
  if (out_at >= 0 && fds[out_at].revents) ReadStdout(on_line);
  if (in_at >= 0 && fds[in_at].revents) {
    const ssize_t w = write(stdin_, pending.data(), pending.size());
    if (w > 0) pending.remove_prefix(static_cast<std::size_t>(w));
    else if (w < 0 && errno != EAGAIN && errno != EINTR) {
      CloseFd(stdin_);  // EPIPE: the child closed its stdin or exited
      const long lines = lines_;
      const std::string exit = WaitForExit();
      throw ChildError("exited before {\"type\":\"done\"} (" + (exit.empty() ? "exit status 0" : exit) +
                       ", after stdout line " + std::to_string(lines) + ", not reading its input)");
    }
  }
  return true;
}

void ChildProcess::Write(std::string_view data, const LineHandler& on_line) {
  if (stdin_ < 0) throw ChildError("the child's input is closed");
  // Fast path: the pipe has room (the usual case, as writes are batched).
  const ssize_t w = write(stdin_, data.data(), data.size());
  if (w > 0) data.remove_prefix(static_cast<std::size_t>(w));
  while (!data.empty()) {
    if (!Pump(data, on_line)) {
      Kill();
      throw ChildError("no progress for " + Seconds(idle_timeout_s_) + " (idle_timeout_s): killed");
    }
  }
}

std::string ChildProcess::WaitForExit() {
  // Read what is left, then reap; a child that closed stdout but lives on gets the
  // idle timeout too.
  std::string_view none;
  const LineHandler ignore = [](std::string_view) {};
  while (stdout_ >= 0 || stderr_ >= 0)
    if (!Pump(none, ignore)) break;
  using Clock = std::chrono::steady_clock;
  const auto deadline = Clock::now() + std::chrono::duration<double>(idle_timeout_s_);
  int status = 0;
  while (waitpid(pid_, &status, WNOHANG) == 0) {
    if (Clock::now() > deadline) {
      Kill();
      return "no exit within " + Seconds(idle_timeout_s_) + " after closing stdout: killed";
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  pid_ = -1;
  if (WIFEXITED(status)) return WEXITSTATUS(status) == 0 ? "" : "exit status " + std::to_string(WEXITSTATUS(status));
  return std::string("killed by signal ") + std::to_string(WTERMSIG(status)) + " (" + strsignal(WTERMSIG(status)) + ")";
}

std::string ChildProcess::CloseAndWait(const LineHandler& on_line) {
  CloseFd(stdin_);
  std::string_view none;
  while (stdout_ >= 0) {
    if (!Pump(none, on_line)) {
      Kill();
      throw ChildError("no progress for " + Seconds(idle_timeout_s_) + " (idle_timeout_s): killed");
    }
  }
  return WaitForExit();
}

}  // namespace slambox
