#pragma once
// Shared by the libFuzzer targets in this folder (one per reader; see README.md). Each target writes
// the input where its reader expects a file, runs the reader, and accepts exactly two outcomes: a
// result, or a prt::Error (the one-line user error). Any other exception escapes and libFuzzer
// reports it as a crash, as it does every sanitizer report, leak, timeout or out-of-memory.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"

namespace prt::fuzz {

/// A per-process scratch folder (in /dev/shm when there is one: inputs are written once per run).
inline const std::string& scratch_dir() {
  static const std::string dir = [] {
    const std::string base = std::filesystem::is_directory("/dev/shm") ? "/dev/shm" : "/tmp";
    std::string d = base + "/prt-fuzz-" + std::to_string(getpid());
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

/// Writes bytes to <scratch>/<name> and returns the path.
inline std::string write_input(const std::uint8_t* data, std::size_t size, const std::string& name) {
  const std::string path = scratch_dir() + "/" + name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

/// Runs a reader; a prt::Error is the expected answer to a bad input and is swallowed.
template <class F>
void expect_result_or_error(F&& read) {
  try {
    read();
  } catch (const prt::Error&) {
  }
}

}  // namespace prt::fuzz
