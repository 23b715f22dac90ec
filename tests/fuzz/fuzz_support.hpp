#pragma once
// The contract every reader harness checks (issue 17): on any input a reader either
// returns a valid object or throws InputError naming the file; anything else (another
// exception, a crash, a sanitizer report, a hang) is a finding. Where a writer exists the
// object must survive a write-read round trip unchanged.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/error.hpp"

namespace slambox::fuzz {

[[noreturn]] inline void Finding(const std::string& what) {
  std::fprintf(stderr, "fuzz contract violated: %s\n", what.c_str());
  std::abort();
}

/// Runs `read` and checks that every error it throws is a proper InputError.
template <class F>
void ExpectCleanResult(F&& read, const char* file) {
  try {
    read();
  } catch (const InputError& e) {
    if (e.file() != file) Finding("InputError names '" + e.file() + "', not the input " + file + ": " + e.what());
    if (std::string(e.what()).size() <= e.file().size() + 2) Finding("InputError without a message");
  }
}

}  // namespace slambox::fuzz
