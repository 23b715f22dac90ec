#pragma once
// One sweep per output folder: a sweep (or a shard of one, or `--merge`) holds an
// exclusive POSIX record lock (fcntl F_SETLK) on DIR/.lock (DIR/.lock.shard-I-of-N for a
// shard, so the shards of a Slurm array run side by side) for as long as it runs. A
// second one on the same folder refuses at once, naming the holder's pid, instead of
// running every run again beside the first. The kernel drops the lock when the sweep
// process ends, also on SIGKILL: no stale lock to clean. The whole-folder lock (a sweep
// without --shard, or --merge) also refuses while any shard of the folder is running. (A record lock, not flock(2):
// it is not inherited by the forked run workers, so it never outlives the sweep.)
#include <string>

namespace slambox {

class SweepLock {
 public:
  /// Throws InputError naming DIR (and the pid holding the lock) when it is taken.
  /// `name` is ".lock" or ".lock.shard-I-of-N".
  SweepLock(const std::string& dir, const std::string& name);
  ~SweepLock();
  SweepLock(const SweepLock&) = delete;
  SweepLock& operator=(const SweepLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace slambox
