// SH basis evaluation speed: sh::eval_batch (float and double, the unrolled fast path) and sh::eval
// (one direction), each against the generic runtime-loop recurrence measured in the same run, for
// bands 1..16 (and the generic path up to kMaxBands). Prints Google Benchmark's table, then one summary
// line per band count with ns per direction, ns per coefficient, the issue's target and the peer
// figures (Sloan, "Efficient Spherical Harmonic Evaluation", JCGT 2(2) 2013, SSE x4 code: constants
// written into this benchmark, not measured here).
//
// Batched runs write to a 64-byte aligned buffer with out_stride = sh::padded_stride(count, sizeof(T)), the
// layout eval_batch is built for; "batch_stride=count" repeats the float fast path with out_stride = count,
// which for count = 1024 or 4096 is a 4 KiB-multiple stride whose rows share L1 cache sets (what the padded
// stride avoids). "fill" writes the same bytes with std::fill: the write bound of a batch, measured in the run.
// Figures in the summary are medians over repetitions of CPU time per direction (the machine is
// shared: CPU time excludes time the process spent descheduled). Usage:
//   bench_sh_eval [--batch=N] [--reps=R] [google benchmark flags, e.g. --benchmark_filter=float]
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstdint>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <glm/vec3.hpp>

#include "sh/basis.h"
#include "sh/eval_kernels.h"

namespace sh = prt::sh;

namespace {

template <typename T>
struct Directions {
  std::vector<T> x, y, z;
};

// `count` uniformly distributed unit directions (fixed seed).
template <typename T>
Directions<T> random_directions(std::size_t count) {
  std::mt19937_64 rng(42);
  std::normal_distribution<double> normal;
  Directions<T> d;
  for (std::size_t j = 0; j < count; ++j) {
    double x = normal(rng), y = normal(rng), z = normal(rng), r = std::sqrt(x * x + y * y + z * z);
    d.x.push_back(static_cast<T>(x / r));
    d.y.push_back(static_cast<T>(y / r));
    d.z.push_back(static_cast<T>(z / r));
  }
  return d;
}

enum class Path { kFast, kGeneric };

// The first `alignment`-byte boundary in `storage` (which has that many bytes of slack).
template <typename T>
T* aligned_start(std::vector<T>& storage, std::size_t alignment) {
  T* p = storage.data();
  while (reinterpret_cast<std::uintptr_t>(p) % alignment != 0) ++p;
  return p;
}

// Output rows `stride` apart in a 64-byte aligned buffer.
template <typename T>
void bench_batch(benchmark::State& state, int bands, Path path, std::size_t count, std::size_t stride) {
  Directions<T> d = random_directions<T>(count);
  std::vector<T> storage(static_cast<std::size_t>(bands * bands) * stride + 64 / sizeof(T));
  T* out = aligned_start(storage, 64);
  for (auto _ : state) {
    if (path == Path::kFast) {
      sh::eval_batch(bands, count, d.x.data(), d.y.data(), d.z.data(), out, stride);
    } else {
      sh::detail::eval_batch_generic(bands, count, d.x.data(), d.y.data(), d.z.data(), out, stride);
    }
    benchmark::DoNotOptimize(out);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * count));
  state.counters["dirs"] = static_cast<double>(count);
}

// The bound of a batched figure: the same output bytes written by std::fill (no arithmetic), in the
// same buffer layout. What the batch takes beyond this is the evaluation's own cost.
template <typename T>
void bench_fill(benchmark::State& state, int bands, std::size_t count, std::size_t stride) {
  std::vector<T> storage(static_cast<std::size_t>(bands * bands) * stride + 64 / sizeof(T));
  T* out = aligned_start(storage, 64);
  T value = static_cast<T>(0.5);
  for (auto _ : state) {
    for (int k = 0; k < bands * bands; ++k) std::fill(out + static_cast<std::size_t>(k) * stride, out + k * stride + count, value);
    value += static_cast<T>(1e-7);
    benchmark::DoNotOptimize(out);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * count));
  state.counters["dirs"] = static_cast<double>(count);
}

// One direction at a time, writing each result over the last (as a caller consuming it would).
template <typename T>
void bench_one(benchmark::State& state, int bands, Path path, std::size_t count) {
  Directions<T> d = random_directions<T>(count);
  std::vector<T> out(static_cast<std::size_t>(bands * bands));
  for (auto _ : state) {
    for (std::size_t j = 0; j < count; ++j) {
      if (path == Path::kFast) {
        sh::eval(bands, glm::vec<3, T>(d.x[j], d.y[j], d.z[j]), out.data());
      } else {
        sh::detail::eval_one_generic(bands, d.x[j], d.y[j], d.z[j], out.data());
      }
      benchmark::DoNotOptimize(out.data());
      benchmark::ClobberMemory();
    }
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * count));
  state.counters["dirs"] = static_cast<double>(count);
}

// Console output plus a record of CPU ns per direction for every iteration run, by benchmark name.
class SummaryReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    benchmark::ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      if (run.run_type != Run::RT_Iteration || run.error_occurred || run.iterations == 0) continue;
      auto dirs = run.counters.find("dirs");
      if (dirs == run.counters.end()) continue;
      double ns = run.cpu_accumulated_time * 1e9 / (static_cast<double>(run.iterations) * dirs->second.value);
      samples_[run.run_name.function_name].push_back(ns);
    }
  }

  /// Median ns per direction of a benchmark, or NAN if it did not run (filtered out).
  double median(const std::string& name) const {
    auto it = samples_.find(name);
    if (it == samples_.end() || it->second.empty()) return NAN;
    std::vector<double> v = it->second;
    std::sort(v.begin(), v.end());
    std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  }

 private:
  std::map<std::string, std::vector<double>> samples_;
};

std::string name_of(const char* kind, const char* type, Path path, int bands) {
  return std::string(kind) + "/" + type + "/" + (path == Path::kFast ? "fast" : "generic") + "/bands:" +
         (bands < 10 ? "0" : "") + std::to_string(bands);
}

// The targets (float, batched, ns per direction) and Sloan's SSE x4 figures, where given.
double target_ns(int bands) { return bands == 3 ? 0.6 : bands == 5 ? 1.6 : bands == 9 ? 6.0 : NAN; }
double sloan_sse_ns(int bands) {
  return bands == 3 ? 0.61 : bands == 5 ? 1.58 : bands == 7 ? 3.35 : bands == 9 ? 6.0 : NAN;
}
// Sloan's scalar code, one direction (float), from the same table.
double sloan_scalar_ns(int bands) {
  return bands == 3 ? 2.1 : bands == 5 ? 6.4 : bands == 7 ? 13.6 : bands == 9 ? 23.2 : NAN;
}

std::string verdict(double value, double target) {
  if (std::isnan(target) || std::isnan(value)) return "";
  return value <= target ? "ok" : "MISS";
}

void print_batch_table(const SummaryReporter& r, std::size_t batch, std::size_t one_count) {
  std::printf("\nSH evaluation, CPU ns per direction (median of repetitions). Batched: %zu directions, SoA output,"
              " out_stride = padded_stride (%zu for float) unless said; 'stride=count' uses out_stride = %zu.\n"
              "Single-direction eval: %zu directions per iteration. Vector lanes: float %zu, double %zu. 'generic' is"
              " the runtime-loop recurrence (eval_batch beyond %d bands), 'x' the fast path's speed-up over it.\n",
              batch, sh::padded_stride(batch, sizeof(float)), batch, one_count, sh::detail::kLanes<float>,
              sh::detail::kLanes<double>, sh::kMaxFastBands);
  std::printf("%5s %5s | %-36s | %-20s | %-26s | %-15s | %-17s | %-30s | %-22s\n", "bands", "coefs",
              "float batch ns/dir ns/coef  target", "stride=count /padded", "write bound ns  B/dir  GB/s",
              "generic      x", "double ns/dir coef", "eval float  generic x  (Sloan)", "eval double generic x");
  for (int bands = 1; bands <= sh::kMaxBands; ++bands) {
    const double n2 = bands * bands;
    const bool fast = bands <= sh::kMaxFastBands;  // eval_batch is the generic path beyond
    double fg = r.median(name_of("batch", "float", Path::kGeneric, bands));
    double dg = r.median(name_of("batch", "double", Path::kGeneric, bands));
    double ff = fast ? r.median(name_of("batch", "float", Path::kFast, bands)) : fg;
    double df = fast ? r.median(name_of("batch", "double", Path::kFast, bands)) : dg;
    double fc = r.median(name_of("batch_stride=count", "float", Path::kFast, bands));
    double fill = r.median(name_of("fill", "float", Path::kFast, bands));
    double of = r.median(name_of("one", "float", Path::kFast, bands));
    double og = r.median(name_of("one", "float", Path::kGeneric, bands));
    double odf = r.median(name_of("one", "double", Path::kFast, bands));
    double odg = r.median(name_of("one", "double", Path::kGeneric, bands));
    if (std::isnan(ff) && std::isnan(fc) && std::isnan(df) && std::isnan(of) && std::isnan(odf)) continue;
    char target[64] = "";
    double t = target_ns(bands), s = sloan_sse_ns(bands);
    if (!std::isnan(t)) {
      std::snprintf(target, sizeof target, "<= %.1f %s", t, verdict(ff, t).c_str());
    } else if (!std::isnan(s)) {
      std::snprintf(target, sizeof target, "(Sloan %.2f)", s);
    }
    char scalar_peer[32] = "";
    if (!std::isnan(sloan_scalar_ns(bands))) std::snprintf(scalar_peer, sizeof scalar_peer, "(%.1f)", sloan_scalar_ns(bands));
    std::printf("%5d %5d | %7.3f %8.4f  %-14s | %7.3f %5.2fx      | %7.3f %6.0f %7.1f   | %7.3f %6.2fx | %7.3f %8.4f | "
                "%7.2f %7.2f %5.2fx %-7s | %7.2f %7.2f %5.2fx\n",
                bands, bands * bands, ff, ff / n2, target, fc, fc / ff, fill, n2 * sizeof(float),
                n2 * sizeof(float) / fill, fg, fg / ff, df, df / n2, of, og, og / of, scalar_peer, odf, odg, odg / odf);
  }
  std::printf("targets (float, batched, per direction): 3 bands <= 0.6 ns, 5 <= 1.6 ns, 9 <= 6 ns; ns/coef flat "
              "up to 16 bands.\n'stride=count /padded': the batch with out_stride = count, and its ratio to the padded "
              "figure. 'write bound': std::fill of the same output bytes (bands^2 x 4 B per "
              "direction, shown) in the padded layout, measured in this run, and the write bandwidth it reaches: a "
              "batch cannot beat it; where the output outgrows the L1 data cache (bands^2 x 4 B x %zu directions) the "
              "batch figure is that bound plus a little, and the targets are bounds on memory, not on evaluation.\n"
              "Peer figures in parentheses are CONSTANTS (Sloan, JCGT 2013, SSE x4 0.61 / 1.58 / 3.35 / 6.0 ns and "
              "scalar 2.1 / 6.4 / 13.6 / 23.2 ns for 3 / 5 / 7 / 9 bands, measured once on this machine kind), not "
              "measured in this run.\n", batch);
}

// Removes "--name=value" from argv and returns value (or fallback).
std::size_t take_flag(int& argc, char** argv, const char* name, std::size_t fallback) {
  const std::size_t len = std::strlen(name);
  for (int i = 1; i < argc; ++i) {
    if (std::strncmp(argv[i], name, len) == 0 && argv[i][len] == '=') {
      std::size_t value = std::strtoull(argv[i] + len + 1, nullptr, 10);
      for (int k = i; k + 1 < argc; ++k) argv[k] = argv[k + 1];
      --argc;
      return value;
    }
  }
  return fallback;
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t batch = take_flag(argc, argv, "--batch", 1024);
  const int reps = static_cast<int>(take_flag(argc, argv, "--reps", 3));
  const std::size_t one_count = 256;
  auto add = [&](const std::string& name, auto fn) {
    benchmark::RegisterBenchmark(name.c_str(), fn)->MinTime(0.05)->Repetitions(reps)->ReportAggregatesOnly(false);
  };
  const std::size_t stride_f = sh::padded_stride(batch, sizeof(float));
  const std::size_t stride_d = sh::padded_stride(batch, sizeof(double));
  for (int bands = 1; bands <= sh::kMaxBands; ++bands) {
    for (Path path : {Path::kFast, Path::kGeneric}) {
      if (path == Path::kFast) {
        add(name_of("batch_stride=count", "float", path, bands),
            [=](benchmark::State& s) { bench_batch<float>(s, bands, path, batch, batch); });
        add(name_of("fill", "float", path, bands), [=](benchmark::State& s) { bench_fill<float>(s, bands, batch, stride_f); });
      }
      // Beyond kMaxFastBands eval_batch is the generic path: measure that once.
      if (bands > sh::kMaxFastBands && path == Path::kFast) continue;
      add(name_of("batch", "float", path, bands),
          [=](benchmark::State& s) { bench_batch<float>(s, bands, path, batch, stride_f); });
      add(name_of("batch", "double", path, bands),
          [=](benchmark::State& s) { bench_batch<double>(s, bands, path, batch, stride_d); });
      if (bands > sh::kMaxFastBands) continue;
      add(name_of("one", "float", path, bands), [=](benchmark::State& s) { bench_one<float>(s, bands, path, one_count); });
      add(name_of("one", "double", path, bands),
          [=](benchmark::State& s) { bench_one<double>(s, bands, path, one_count); });
    }
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  SummaryReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  print_batch_table(reporter, batch, one_count);
  benchmark::Shutdown();
  return 0;
}
