#include "dist/mpi_launch.h"

#include <spawn.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

extern char** environ;

namespace prt::test {

std::string mpirun(int ranks) { return std::string(PRT_MPIEXEC) + " --oversubscribe -np " + std::to_string(ranks); }

RunResult run_prt_ranks(int ranks, const std::string& arguments) {
  return run_shell(mpirun(ranks) + " " + prt_binary() + " " + arguments);
}

pid_t spawn_shell(const std::string& command, const std::string& log) {
  const std::string line = command + " >" + log + " 2>&1";
  const char* argv[] = {"/bin/sh", "-c", line.c_str(), nullptr};
  pid_t pid = -1;
  if (posix_spawn(&pid, "/bin/sh", nullptr, nullptr, const_cast<char* const*>(argv), environ) != 0) return -1;
  return pid;
}

namespace {

// Fields of /proc/<pid>/stat after the command name: state, ppid.
bool read_stat(pid_t pid, char& state, pid_t& parent) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t close = text.rfind(')');
  if (close == std::string::npos) return false;
  std::istringstream rest(text.substr(close + 1));
  return static_cast<bool>(rest >> state >> parent);
}

}  // namespace

std::vector<pid_t> children_of(pid_t parent) {
  std::vector<pid_t> out;
  for (const auto& entry : std::filesystem::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    char state = 0;
    pid_t ppid = 0;
    if (read_stat(std::stoi(name), state, ppid) && ppid == parent) out.push_back(std::stoi(name));
  }
  return out;
}

int mpi_rank_of(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/environ");
  std::string variable;
  const std::string key = "OMPI_COMM_WORLD_RANK=";
  while (std::getline(in, variable, '\0'))
    if (variable.compare(0, key.size(), key) == 0) return std::stoi(variable.substr(key.size()));
  return -1;
}

bool running(pid_t pid) {
  char state = 0;
  pid_t parent = 0;
  return read_stat(pid, state, parent) && state != 'Z' && state != 'X';
}

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

}  // namespace prt::test
