#include "app/sweep_exec.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "app/run.hpp"
#include "core/atomic_file.hpp"
#include "core/file_status.hpp"

namespace slambox {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

std::string RunDir(const std::string& out_dir, const SweepRun& run) { return out_dir + "/runs/" + run.id; }

bool RunComplete(const std::string& out_dir, const SweepRun& run) {
  const std::string dir = RunDir(out_dir, run);
  return PathExists(dir + "/metrics.json") || PathExists(dir + "/failed.json");
}

namespace {

struct Running {
  const SweepRun* run;
  Clock::time_point start;
  bool killed_for_timeout = false;
};

std::string Join(const std::vector<std::string>& v, const std::string& sep) {
  std::string out;
  for (const auto& s : v) out += (out.empty() ? "" : sep) + s;
  return out;
}

pid_t Launch(const SweepRun& run, const ExecOptions& o) {
  const std::string dir = RunDir(o.out_dir, run);
  fs::create_directories(dir);
  std::vector<std::string> args = {o.worker_exe, "run", run.scenario, "--algo", Join(o.algorithms, ","), "-o", dir,
                                   "--no-figures", "-q", "--skip-unavailable"};
  if (o.pictures) args.push_back("--sweep-pictures");
  if (!run.is_stream) args.insert(args.end(), {"--seed", std::to_string(run.seed)});
  if (!run.relations.empty()) args.insert(args.end(), {"--relations", run.relations});
  for (const auto& s : run.sets) {
    args.push_back("--set");
    args.push_back(s);
  }
  for (const auto& p : o.plugins) {
    args.push_back("--plugin");
    args.push_back(p);
  }
  const std::string log = dir + "/log.txt";
  const pid_t parent = getpid();
  if (o.fork_hooks.before) o.fork_hooks.before();
  const pid_t pid = fork();
  if (pid != 0 && o.fork_hooks.after_in_parent) o.fork_hooks.after_in_parent();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    if (o.fork_hooks.after_in_child) o.fork_hooks.after_in_child();
    setpgid(0, 0);                   // own group: a timeout kills the run and its children
    prctl(PR_SET_PDEATHSIG, SIGKILL);  // a killed sweep leaves no orphan runs behind
    if (getppid() != parent) _exit(126);  // the sweep died before prctl took effect
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      dup2(fd, STDOUT_FILENO);
      dup2(fd, STDERR_FILENO);
      close(fd);
    }
    if (o.worker_exe.empty()) {
      // The forked sweep runs the run itself: no exec, so none of the ~0.2 s it takes to
      // load slambox's shared libraries (MRPT's among them) per run.
      RunRequest request;
      request.input = run.scenario;
      request.seed = run.seed;
      request.seed_given = !run.is_stream;
      request.relations_path = run.relations;
      request.sets = run.sets;
      request.algorithms = o.algorithms;
      request.output_dir = dir;
      request.figures = false;
      request.pictures = o.pictures;
      request.quiet = true;
      request.skip_unavailable = true;
      int code = 0;
      try {
        RunAndWrite(request);
      } catch (const std::exception& e) {
        std::fprintf(stderr, "slambox: error: %s\n", e.what());
        code = 2;
      }
      std::fflush(nullptr);
      _exit(code);
    }
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  setpgid(pid, pid);
  return pid;
}

std::string LogTail(const std::string& path, std::size_t max_chars = 600) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  std::string text = s.str();
  if (text.size() > max_chars) text = "..." + text.substr(text.size() - max_chars);
  return text;
}

std::string Duration(double s) {
  char buf[32];
  const long t = static_cast<long>(s + 0.5);
  std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", t / 3600, (t / 60) % 60, t % 60);
  return buf;
}

}  // namespace

ExecSummary ExecuteRuns(const std::vector<SweepRun>& runs, const ExecOptions& o) {
  ExecSummary summary;
  std::deque<const SweepRun*> pending;
  for (const auto& r : runs) {
    if (RunComplete(o.out_dir, r)) ++summary.skipped;
    else pending.push_back(&r);
  }
  const std::size_t total = pending.size();
  std::map<pid_t, Running> running;
  const auto t0 = Clock::now();
  auto report = [&](const SweepRun& run, const std::string& status, double seconds) {
    if (o.quiet) return;
    const int done = summary.executed;
    const double elapsed = std::chrono::duration<double>(Clock::now() - t0).count();
    const double eta = done > 0 ? elapsed / done * (total - done) : 0.0;
    if (o.progress_bar) {
      const int width = 30, filled = total ? static_cast<int>(width * done / total) : width;
      std::fprintf(stderr, "\r[%s%s] %d/%zu runs, %d failed, ETA %s ", std::string(filled, '#').c_str(),
                   std::string(width - filled, '-').c_str(), done, total, summary.failed, Duration(eta).c_str());
      if (static_cast<std::size_t>(done) == total) std::fputc('\n', stderr);
    } else {
      std::fprintf(stderr, "sweep: %d/%zu %s %s seed %llu %s (%.1f s)\n", done, total, run.id.c_str(),
                   run.scenario.c_str(), static_cast<unsigned long long>(run.seed), status.c_str(), seconds);
    }
  };
  while (!pending.empty() || !running.empty()) {
    while (!pending.empty() && static_cast<int>(running.size()) < o.jobs) {
      const SweepRun* run = pending.front();
      pending.pop_front();
      running[Launch(*run, o)] = {run, Clock::now()};
    }
    int status = 0;
    const pid_t pid = waitpid(-1, &status, WNOHANG);
    if (pid > 0 && running.count(pid)) {
      const Running r = running[pid];
      running.erase(pid);
      kill(-pid, SIGKILL);  // anything the run left in its group
      const double seconds = std::chrono::duration<double>(Clock::now() - r.start).count();
      const std::string dir = RunDir(o.out_dir, *r.run);
      ++summary.executed;
      if (PathExists(dir + "/metrics.json")) {
        report(*r.run, "ok", seconds);
        continue;
      }
      std::string reason;
      if (r.killed_for_timeout) reason = "timeout after " + std::to_string(static_cast<int>(o.timeout_s)) + " s";
      else if (WIFSIGNALED(status)) reason = "crashed with signal " + std::to_string(WTERMSIG(status));
      else reason = "exit code " + std::to_string(WEXITSTATUS(status));
      const nlohmann::json failed = {{"status", "failed"}, {"reason", reason}, {"log_tail", LogTail(dir + "/log.txt")}};
      WriteFileAtomic(dir + "/failed.json", failed.dump(1) + "\n");
      ++summary.failed;
      report(*r.run, "FAILED: " + reason, seconds);
      continue;
    }
    for (auto& [p, r] : running) {
      if (!r.killed_for_timeout && std::chrono::duration<double>(Clock::now() - r.start).count() > o.timeout_s) {
        kill(-p, SIGKILL);
        r.killed_for_timeout = true;
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return summary;
}

}  // namespace slambox
