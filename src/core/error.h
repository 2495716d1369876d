#pragma once
// Errors that reach the user. Every failure caused by input (a file, an argument) is reported as one
// line: "<file>: <problem>" when a file is involved, else "<problem>". The CLI prints it after "prt: "
// and exits with status 1.
#include <stdexcept>
#include <string>

namespace prt {

/// A user-facing failure with a one-line message (no trailing newline).
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message);
};

/// Throws Error("<path>: <problem>").
[[noreturn]] void fail_file(const std::string& path, const std::string& problem);

/// Throws Error(problem).
[[noreturn]] void fail(const std::string& problem);

}  // namespace prt
