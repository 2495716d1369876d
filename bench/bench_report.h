#pragma once
// What benchmarks with a summary table share: a console reporter that keeps every run's wall and
// main-thread CPU time per iteration (ms) by name, a lookup, and the Google Benchmark main sequence.
#include <benchmark/benchmark.h>

#include <map>
#include <string>
#include <vector>

namespace bench {

class RecordingReporter : public benchmark::ConsoleReporter {
 public:
  std::map<std::string, double> ms, cpu_ms;
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs)
      if (run.run_type == Run::RT_Iteration && !run.error_occurred) {
        ms[run.benchmark_name()] = run.GetAdjustedRealTime();
        cpu_ms[run.benchmark_name()] = run.GetAdjustedCPUTime();
      }
    ConsoleReporter::ReportRuns(runs);
  }
};

/// The recorded time of run `name`, or -1 if it did not run (filtered out).
inline double lookup(const std::map<std::string, double>& times, const std::string& name) {
  auto it = times.find(name);
  return it == times.end() ? -1.0 : it->second;
}

/// Initialize, run every selected benchmark through `reporter`, shut down. False for unknown arguments.
inline bool run_benchmarks(int& argc, char** argv, RecordingReporter& reporter) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return false;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return true;
}

}  // namespace bench
