#include "core/atomic_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace slambox {

void WriteFileAtomic(const std::string& path, const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  if (target.has_parent_path()) fs::create_directories(target.parent_path());
  const fs::path tmp = target.string() + ".tmp." + std::to_string(::getpid());
  // errno of the failed write (ENOSPC on a full disk) names the cause; the target is untouched.
  auto failed = [&](const char* what) {
    const int err = errno;
    return std::runtime_error(std::string(what) + " " + target.string() + ": " +
                              (err ? std::strerror(err) : "I/O error") + " (the file was not changed)");
  };
  try {
    {
      errno = 0;
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      if (!out) throw failed("cannot create a temporary file to write");
      write(out);
      out.flush();
      if (!out) throw failed("cannot write");
      out.close();
      if (!out) throw failed("cannot write");
    }
    fs::rename(tmp, target);
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
}

void WriteFileAtomic(const std::string& path, const std::string& content) {
  WriteFileAtomic(path, [&](std::ostream& out) { out << content; });
}

}  // namespace slambox
