#pragma once
// Runs the real `prt` binary from tests and captures what it printed.
#include <string>

namespace prt::test {

struct RunResult {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr together
};

/// Runs "<build>/src/cli/prt <arguments>" through the shell (arguments are not quoted for you).
RunResult run_prt(const std::string& arguments);

/// Runs a shell command line, capturing stdout and stderr together.
RunResult run_shell(const std::string& command);

/// True if the run exited with status 1 after printing exactly one line that contains `expected` (the
/// project's rule for bad input).
bool fails_in_one_line(const RunResult& result, const std::string& expected);

/// rel_rms of image `image` against `reference` as `prt compare` prints it. Throws std::runtime_error
/// with prt's output if the comparison fails.
double compare_rel_rms(const std::string& image, const std::string& reference);

/// Path of the prt binary in the build tree.
std::string prt_binary();

/// A fresh empty folder under the system temp dir, named after `name` and this process (pid), so
/// test cases that ctest runs in parallel never share one.
std::string fresh_temp_dir(const std::string& name);

/// Number of entries in a folder (to check that nothing, not even a temporary, was left behind).
std::size_t entries_in(const std::string& dir);

}  // namespace prt::test
