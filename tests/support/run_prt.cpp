#include "support/run_prt.h"

#include <array>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include <unistd.h>

#include <sys/wait.h>

namespace prt::test {

std::string prt_binary() { return std::string(PRT_BINARY_DIR) + "/src/cli/prt"; }

RunResult run_prt(const std::string& arguments) { return run_shell(prt_binary() + " " + arguments); }

double compare_rel_rms(const std::string& image, const std::string& reference) {
  const RunResult r = run_prt("compare " + image + " " + reference);
  const std::size_t at = r.output.find("rel_rms=");
  if (r.exit_code != 0 || at == std::string::npos) throw std::runtime_error("prt compare " + image + " " + reference + ": " + r.output);
  return std::stod(r.output.substr(at + 8));
}

RunResult run_shell(const std::string& command) {
  RunResult result;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer;
  std::size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return result;
}

std::string fresh_temp_dir(const std::string& name) {
  namespace fs = std::filesystem;
  // One folder per process: ctest runs each test case as its own process, in parallel, and two cases
  // of one file must not clear each other's folder.
  fs::path dir = fs::temp_directory_path() / "prt_tests" / (name + "-" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir.string();
}

std::size_t entries_in(const std::string& dir) {
  std::size_t count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    (void)entry;
    ++count;
  }
  return count;
}

bool fails_in_one_line(const RunResult& result, const std::string& expected) {
  std::size_t lines = 0;
  for (char c : result.output) lines += c == '\n';
  return result.exit_code == 1 && result.output.find(expected) != std::string::npos && lines == 1;
}

}  // namespace prt::test
