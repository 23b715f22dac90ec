#include "app/sweep_lock.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>

#include "core/error.hpp"

namespace slambox {
namespace {

/// The pid holding a write lock on `path`, or 0 when none does.
pid_t Holder(int fd) {
  struct flock q {};
  q.l_type = F_WRLCK;
  q.l_whence = SEEK_SET;
  return ::fcntl(fd, F_GETLK, &q) == 0 && q.l_type != F_UNLCK ? q.l_pid : 0;
}

[[noreturn]] void Busy(const std::string& dir, const std::string& path, pid_t pid) {
  throw InputError(dir, 0,
                   "another slambox sweep is running on this folder" +
                       (pid > 0 ? " (pid " + std::to_string(pid) + ")" : std::string()) + " and holds " + path,
                   "wait for it to finish (then add --resume if it was stopped), or give a new -o folder");
}

}  // namespace

SweepLock::SweepLock(const std::string& dir, const std::string& name) {
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/" + name;
  // The whole-folder lock (a sweep, --merge) also waits for no shard to be running.
  if (name == ".lock")
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
      const std::string file = entry.path().filename().string();
      if (file.rfind(".lock.shard-", 0) != 0) continue;
      const int fd = ::open(entry.path().c_str(), O_RDONLY | O_CLOEXEC);
      if (fd < 0) continue;
      struct flock q {};
      q.l_type = F_RDLCK;  // F_GETLK with a read lock reports any write lock
      q.l_whence = SEEK_SET;
      const bool held = ::fcntl(fd, F_GETLK, &q) == 0 && q.l_type != F_UNLCK;
      ::close(fd);
      if (held) Busy(dir, entry.path().string(), q.l_pid);
    }
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw InputError(dir, 0, "cannot create the sweep lock " + path + ": " + std::strerror(errno),
                     "give an output folder you can write to");
  struct flock lock {};
  lock.l_type = F_WRLCK;
  lock.l_whence = SEEK_SET;  // l_start = l_len = 0: the whole file
  if (::fcntl(fd_, F_SETLK, &lock) != 0) {
    const int err = errno;
    const pid_t pid = Holder(fd_);
    ::close(fd_);
    fd_ = -1;
    if (err != EACCES && err != EAGAIN)
      throw InputError(dir, 0, "cannot lock " + path + ": " + std::strerror(err), "give a local output folder");
    Busy(dir, path, pid);
  }
}

SweepLock::~SweepLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the flock
}

}  // namespace slambox
