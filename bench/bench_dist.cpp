// bench_dist: distributed baking (docs/distributed.md) through the real binaries, in one run.
//
// Mesh: bench::cornell_box(C) (default C = 295: 435,824 vertices, the ~437k class; a closed room, so
// most bounce rays hit), written as PLY. Bake: prt bake --transfer interreflected --bands 5 --samples S
// --bounces B (defaults 64 and 2: three passes, each followed by an allgather of 25 floats per vertex).
//   1. Overhead (issue 14): `mpirun -np 2 --bind-to none prt bake --threads 1` against
//      `prt bake --threads 2` (one process); runs alternate A B A B, each pair gives a ratio
//      t(1 process x 2 threads) / t(2 ranks x 1 thread) (target >= 0.9), of wall time and of CPU time;
//      the medians are printed. The outputs must be byte-identical.
//   2. Scaling model: mpirun -np 1, 2, 3 (1 thread each; 3 ranks oversubscribe 2 cores): per pass, the
//      bytes rank 0 exchanged and the seconds the exchange took (after the barrier), against the pass's
//      compute; peak resident memory of the largest rank.
// A timed program, not Google Benchmark: each bake takes tens of seconds; the machine is shared, so the
// ratios of runs measured back to back are what counts (the load average is printed).
// Usage: bench_dist [--cells C] [--samples S] [--bounces B] [--repeat R] [--scaling 0|1] (0: part 1 only)
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "bench_meshes.h"
#include "mesh/writers.h"

namespace {

struct Args {
  int cells = 295, samples = 64, bounces = 2, repeat = 3, scaling = 1;
};

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    int* target = !std::strcmp(argv[i], "--cells")     ? &a.cells
                  : !std::strcmp(argv[i], "--samples") ? &a.samples
                  : !std::strcmp(argv[i], "--bounces") ? &a.bounces
                  : !std::strcmp(argv[i], "--repeat")  ? &a.repeat
                  : !std::strcmp(argv[i], "--scaling") ? &a.scaling
                                                       : nullptr;
    if (!target || i + 1 >= argc) {
      std::fprintf(stderr, "usage: bench_dist [--cells C] [--samples S] [--bounces B] [--repeat R] [--scaling 0|1]\n");
      std::exit(2);
    }
    *target = std::atoi(argv[++i]);
  }
  return a;
}

struct Run {
  double seconds = 0;        // wall time of the whole command
  double cpu_seconds = 0;    // user + system time of all its processes
  double bake_seconds = 0;   // prt's own figure (after loading)
  double exchanged_mb = 0, exchange_seconds = 0, wait_seconds = 0;  // rank 0's, all passes
  double peak_mib = 0;       // largest resident set of the command's processes
  std::string output;
};

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  std::string a, b, c;
  in >> a >> b >> c;
  return a + " " + b + " " + c;
}

// Runs `command` through /bin/sh with stderr captured; wall time and the peak RSS of its descendants.
Run run(const std::string& command, const std::string& log) {
  Run r;
  const auto start = std::chrono::steady_clock::now();
  const std::string rss_file = log + ".rss";
  const pid_t pid = fork();
  if (pid == 0) {
    // A fresh process whose RUSAGE_CHILDREN covers this command alone (the shell, mpirun and its ranks).
    const pid_t shell = fork();
    if (shell == 0) {
      const std::string line = command + " 2>" + log;
      execl("/bin/sh", "sh", "-c", line.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    int shell_status = 0;
    waitpid(shell, &shell_status, 0);
    rusage children{};
    getrusage(RUSAGE_CHILDREN, &children);
    const double cpu = children.ru_utime.tv_sec + children.ru_stime.tv_sec +
                       1e-6 * (children.ru_utime.tv_usec + children.ru_stime.tv_usec);
    std::ofstream(rss_file) << children.ru_maxrss << " " << cpu;
    _exit(WIFEXITED(shell_status) ? WEXITSTATUS(shell_status) : 1);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  long rss_kib = 0;
  std::ifstream(rss_file) >> rss_kib >> r.cpu_seconds;
  r.peak_mib = static_cast<double>(rss_kib) / 1024.0;
  std::ifstream in(log);
  r.output.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::fprintf(stderr, "bench_dist: failed: %s\n%s", command.c_str(), r.output.c_str());
    std::exit(1);
  }
  // "... N ranks (rank 0: X MB exchanged in E s after waiting W s for the others), T s -> out"
  const std::size_t at = r.output.find("(rank 0: ");
  if (at != std::string::npos)
    std::sscanf(r.output.c_str() + at, "(rank 0: %lf MB exchanged in %lf s after waiting %lf s for the others), %lf s",
                &r.exchanged_mb, &r.exchange_seconds, &r.wait_seconds, &r.bake_seconds);
  else if (const std::size_t s = r.output.rfind(", "); s != std::string::npos)
    std::sscanf(r.output.c_str() + s, ", %lf s", &r.bake_seconds);
  return r;
}

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

int main(int argc, char** argv) {
  const Args a = parse(argc, argv);
  const std::string dir = (std::filesystem::temp_directory_path() / "prt_bench_dist").string();
  std::filesystem::create_directories(dir);
  const prt::mesh::Mesh mesh = prt::bench::cornell_box(a.cells);
  const std::string mesh_path = dir + "/cornell.ply";
  prt::mesh::write_ply(mesh_path, mesh.positions, {}, mesh.indices);
  const int passes = 1 + a.bounces;
  std::printf("bench_dist: cornell_box(%d): %zu vertices, %zu triangles; interreflected, 5 bands, %d samples, %d bounces (%d passes)\n",
              a.cells, mesh.positions.size(), mesh.indices.size() / 3, a.samples, a.bounces, passes);
  std::printf("load average at start: %s\n", load_average().c_str());

  const std::string prt = std::string(PRT_BINARY_DIR) + "/src/cli/prt";
  const std::string mpirun = std::string(PRT_MPIEXEC) + " --oversubscribe -np ";
  const std::string bake = " bake " + mesh_path + " --transfer interreflected --bands 5 --samples " + std::to_string(a.samples) +
                           " --bounces " + std::to_string(a.bounces);
  // 1. Overhead: alternate the two configurations; each pair, run back to back, gives one ratio. The
  // ranks are not pinned to cores (--bind-to none), like the single process's threads.
  std::vector<double> wall_ratios, cpu_ratios;
  for (int k = 0; k < a.repeat; ++k) {
    const Run s = run(prt + bake + " --threads 2 -o " + dir + "/single.prt", dir + "/single.log");
    const Run m = run(mpirun + "2 --bind-to none " + prt + bake + " --threads 1 -o " + dir + "/ranks2.prt", dir + "/ranks2.log");
    std::printf("  pair %d: 1 process x 2 threads %.2f s (%.1f CPU s), 2 ranks x 1 thread %.2f s (%.1f CPU s; rank 0 waited %.2f s, "
                "exchanged %.2f s)\n",
                k + 1, s.seconds, s.cpu_seconds, m.seconds, m.cpu_seconds, m.wait_seconds, m.exchange_seconds);
    wall_ratios.push_back(s.seconds / m.seconds);
    cpu_ratios.push_back(s.cpu_seconds / m.cpu_seconds);
  }
  const auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
  };
  const bool identical = bytes_of(dir + "/single.prt") == bytes_of(dir + "/ranks2.prt");
  std::printf("\n%-60s %8s %8s\n", "t(1 process x 2 threads) / t(2 ranks x 1 thread), median", "ratio", "target");
  std::printf("%-60s %8.3f %8s\n", "  wall time of the whole command (load, bake, write)", median(wall_ratios), ">=0.9");
  std::printf("%-60s %8.3f %8s\n", "  CPU time of all processes (robust to other load)", median(cpu_ratios), "");
  std::printf("outputs byte-identical: %s\n", identical ? "yes" : "NO");

  // 2. Scaling model: bytes and time per exchange against compute per pass.
  std::printf("\n%-6s %10s %12s %12s %12s %12s %10s\n", "ranks", "bake s", "MB/exchange", "s/exchange", "wait s/pass",
              "compute s/pass", "peak MiB");
  for (int ranks = 1; ranks <= (a.scaling ? 3 : 0); ++ranks) {
    const Run r = run(mpirun + std::to_string(ranks) + " --bind-to none " + prt + bake + " --threads 1 -o " + dir + "/np.prt", dir + "/np.log");
    const double compute = (r.bake_seconds - r.exchange_seconds - r.wait_seconds) / passes;
    std::printf("%-6d %10.2f %12.2f %12.4f %12.3f %12.2f %10.0f\n", ranks, r.bake_seconds, r.exchanged_mb / passes,
                r.exchange_seconds / passes, r.wait_seconds / passes, compute, r.peak_mib);
  }
  std::printf("\nload average at end: %s\n", load_average().c_str());
  std::filesystem::remove_all(dir);
  return identical ? 0 : 1;
}
