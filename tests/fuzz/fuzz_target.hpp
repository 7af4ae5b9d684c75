#pragma once
// Shared shape of ccdlab's libFuzzer targets (experiments/scripts/fuzz.sh): a reader gets arbitrary bytes and
// must either return a valid result or throw ccdlab::Error. Anything else — another exception, a crash, a
// sanitizer report, an allocation past libFuzzer's -rss_limit_mb or -malloc_limit_mb — is a finding.
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

#include <unistd.h>

#include "framework/util/error.hpp"

namespace ccdlab::fuzz {

/// A private scratch path (in /dev/shm when present) for readers that take a path.
inline std::string scratch_path(const std::string& name) {
  static const std::string dir = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
  return dir + "/ccdlab_fuzz_" + std::to_string(getpid()) + "_" + name;
}

/// Writes the input to scratch_path(name) and returns that path.
inline std::string write_input(const std::uint8_t* data, std::size_t size, const std::string& name) {
  const std::string path = scratch_path(name);
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data), std::streamsize(size));
  return path;
}

/// Runs `f`; a ccdlab::Error is the expected answer to bad input, every other exception escapes (a finding).
template <class F>
int expect_result_or_error(F&& f) {
  try {
    f();
  } catch (const Error&) {
  }
  return 0;
}

}  // namespace ccdlab::fuzz
