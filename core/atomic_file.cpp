#include "core/atomic_file.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace slambox {

void WriteFileAtomic(const std::string& path, const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  if (target.has_parent_path()) fs::create_directories(target.parent_path());
  const fs::path tmp = target.string() + ".tmp." + std::to_string(::getpid());
  try {
    {
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      if (!out) throw std::runtime_error("cannot open " + tmp.string() + " for writing");
      write(out);
      out.flush();
      if (!out) throw std::runtime_error("write failed: " + tmp.string());
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
