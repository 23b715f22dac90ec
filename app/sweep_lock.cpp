#include "app/sweep_lock.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>

#include "core/error.hpp"

namespace slambox {

SweepLock::SweepLock(const std::string& dir, const std::string& name) {
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/" + name;
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw InputError(dir, 0, "cannot create the sweep lock " + path + ": " + std::strerror(errno),
                     "give an output folder you can write to");
  struct flock lock {};
  lock.l_type = F_WRLCK;
  lock.l_whence = SEEK_SET;  // l_start = l_len = 0: the whole file
  if (::fcntl(fd_, F_SETLK, &lock) != 0) {
    const int err = errno;
    struct flock holder {};
    holder.l_type = F_WRLCK;
    holder.l_whence = SEEK_SET;
    const bool known = ::fcntl(fd_, F_GETLK, &holder) == 0 && holder.l_type != F_UNLCK;
    ::close(fd_);
    fd_ = -1;
    if (err != EACCES && err != EAGAIN)
      throw InputError(dir, 0, "cannot lock " + path + ": " + std::strerror(err), "give a local output folder");
    throw InputError(dir, 0,
                     "another slambox sweep is running on this folder" +
                         (known ? " (pid " + std::to_string(holder.l_pid) + ")" : std::string()) + " and holds " + path,
                     "wait for it to finish (then add --resume if it was stopped), or give a new -o folder");
  }
}

SweepLock::~SweepLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the flock
}

}  // namespace slambox
