#pragma once
// Launching `prt` under mpirun from the distributed tests, and watching its ranks (Linux /proc).
#include <string>
#include <sys/types.h>
#include <vector>

#include "support/run_prt.h"

namespace prt::test {

/// "mpirun --oversubscribe -np <ranks>" (the launcher CMake found; more ranks than cores are fine).
std::string mpirun(int ranks);

/// "mpirun ... -np <ranks> <prt> <arguments>", run through the shell.
RunResult run_prt_ranks(int ranks, const std::string& arguments);

/// Starts `command` with /bin/sh in the background (stdout and stderr to `log`); returns its pid, which
/// is the launcher's own when the command starts with "exec".
pid_t spawn_shell(const std::string& command, const std::string& log);

/// The pids whose parent is `parent`.
std::vector<pid_t> children_of(pid_t parent);

/// OMPI_COMM_WORLD_RANK of a process started by Open MPI's mpirun, -1 if it has none (or is gone).
int mpi_rank_of(pid_t pid);

/// True if `pid` exists and is not a zombie.
bool running(pid_t pid);

/// The whole file as bytes ("" if it does not exist).
std::string file_bytes(const std::string& path);

}  // namespace prt::test
