// SH basis evaluation speed: sh::eval_batch (float and double, the unrolled fast path) and sh::eval
// (one direction), each against the generic runtime-loop recurrence measured in the same run, for
// bands 1..16 (and the generic path up to kMaxBands). Prints Google Benchmark's table, then one summary
// line per band count with ns per direction, ns per coefficient, the issue's target and the peer
// figures (Sloan, "Efficient Spherical Harmonic Evaluation", JCGT 2(2) 2013, SSE x4 code: constants
// written into this benchmark, not measured here).
//
// Batched runs write to a 64-byte aligned buffer with out_stride = sh::padded_stride(count, sizeof(T)), the
// recommended layout; "batch_stride=count" repeats the float fast path with out_stride = count, which
// for count = 1024 or 4096 is the cache-hostile 4 KiB-multiple stride (eval_batch's path for crowded strides).
// "fill" writes the same bytes with std::fill: the write bound of a batch, measured in the run.
// "placed_ratio_in@B": the float batch at out_stride = count over the padded one, paired, with the rows on a
// page boundary and the inputs B bytes past one (the table 'inputs placed'), 2-32 bands.
// "fused_dirs=N" is sh::eval_accumulate over N directions per call (evaluation fused with weighted
// accumulation into bands^2 sums, as projection uses it): the figure that does not depend on the cache.
// "stream_dirs=N" is sh::Accumulator fed N directions per call, the batch's directions in all, reduced once:
// the fused path for directions that arrive in short calls.
// Figures in the summary are medians over repetitions of CPU time per direction (the machine is
// shared: CPU time excludes time the process spent descheduled). Usage:
//   bench_sh_eval [--batch=N] [--reps=R] [google benchmark flags, e.g. --benchmark_filter=float]
#include <algorithm>
#include <chrono>
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

#include "sh/accumulator.h"
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

// The float batch at out_stride = count against the padded stride, with both outputs' rows on a page
// boundary and x, y, z `offset` bytes past one (whole pages apart, so all three at that page offset): one
// placement of the inputs against the rows. Loads whose address matches a pending store's in the low 12
// bits wait for it (4K aliasing), so a path's speed can depend on where the caller's inputs lie. The two
// strides alternate, 1 + 4 calls each (4 timed), and the counter "ratio" is the median over the iterations
// of the crowded time over the padded time: paired, so that the machine's drifts cancel.
void bench_placed_ratio(benchmark::State& state, int bands, std::size_t count, std::size_t offset) {
  using Clock = std::chrono::steady_clock;
  const Directions<float> d = random_directions<float>(count);
  const std::size_t page = 4096 / sizeof(float);  // floats per page
  const std::size_t span = (count + offset / sizeof(float) + page - 1) / page * page;
  std::vector<float> in_storage(3 * span + page);
  float* x = aligned_start(in_storage, 4096) + offset / sizeof(float);
  float *y = x + span, *z = y + span;
  std::copy(d.x.begin(), d.x.end(), x);
  std::copy(d.y.begin(), d.y.end(), y);
  std::copy(d.z.begin(), d.z.end(), z);
  const std::size_t padded = sh::padded_stride(count, sizeof(float)), rows = static_cast<std::size_t>(bands * bands);
  std::vector<float> crowded_storage(rows * count + page), padded_storage(rows * padded + page);
  float *crowded_out = aligned_start(crowded_storage, 4096), *padded_out = aligned_start(padded_storage, 4096);
  std::vector<double> ratios;
  // Four timed calls after an untimed one, which brings that output back into the caches from where the
  // other stride's calls pushed it (the steady state of a caller that reuses its buffer).
  auto time_calls = [&](float* out, std::size_t stride) {
    sh::eval_batch(bands, count, x, y, z, out, stride);
    benchmark::ClobberMemory();
    const auto start = Clock::now();
    for (int i = 0; i < 4; ++i) {
      sh::eval_batch(bands, count, x, y, z, out, stride);
      benchmark::ClobberMemory();
    }
    return std::chrono::duration<double>(Clock::now() - start).count();
  };
  for (auto _ : state) {
    const double padded_time = time_calls(padded_out, padded);
    ratios.push_back(time_calls(crowded_out, count) / padded_time);
  }
  std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
  state.counters["ratio"] = ratios.empty() ? NAN : ratios[ratios.size() / 2];
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

// The bound of eval_batch's path for crowded strides (out_stride = count = 1024): the same bytes written by
// std::fill in its order: tile by tile (sh::detail::staged_tile_directions), sh::detail::staged_pass_rows
// rows at a time, a vector of directions (64 bytes) into each of them in turn along the tile. The value comes
// from a register: copied from a stack array, its loads waited on the pending row stores whenever the array's
// page offset came round (4K aliasing), which made this bound 1.25-1.85x the padded batch on Zen 3.
template <typename T>
void bench_fill_tiled(benchmark::State& state, int bands, std::size_t count, std::size_t stride) {
  std::vector<T> storage(static_cast<std::size_t>(bands * bands) * stride + 64 / sizeof(T));
  T* out = aligned_start(storage, 64);
  constexpr std::size_t width = 64 / sizeof(T);
  const std::size_t tile = sh::detail::staged_tile_directions(bands, count, sizeof(T));
  const int rows = bands * bands, pass = sh::detail::staged_pass_rows(bands);
  T value = static_cast<T>(0.5);
  for (auto _ : state) {
    for (std::size_t j = 0; j < count; j += tile) {
      const std::size_t end = std::min(count, j + tile);
      for (int k0 = 0; k0 < rows; k0 += pass) {
        const int k1 = std::min(rows, k0 + pass);
        if (pass == 1) {
          std::fill(out + k0 * stride + j, out + k0 * stride + end, value);
          continue;
        }
        T* const first = out + static_cast<std::size_t>(k0) * stride;
        const std::size_t in_pass = static_cast<std::size_t>(k1 - k0) * stride;
        std::size_t i = j;
        for (; i + width <= end; i += width)
          for (T* p = first + i; p < first + in_pass; p += stride) std::fill_n(p, width, value);
        for (T* p = first; p < first + in_pass; p += stride) std::fill(p + i, p + end, value);
      }
    }
    value += static_cast<T>(1e-7);
    benchmark::DoNotOptimize(out);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * count));
  state.counters["dirs"] = static_cast<double>(count);
}

// Evaluation where projection uses it: fused with accumulation. sh::eval_accumulate adds
// sum_j w_j Y_k(d_j) into bands^2 sums (or the generic recurrence's values, weighted, for 'generic'), so
// nothing per direction is stored and only the 16 input bytes per direction are read.
template <typename T>
void bench_fused(benchmark::State& state, int bands, Path path, std::size_t count) {
  Directions<T> d = random_directions<T>(count);
  std::vector<T> weight(count);
  for (std::size_t j = 0; j < count; ++j) weight[j] = static_cast<T>(0.5 + 0.25 * d.x[j]);
  std::vector<T> sums(static_cast<std::size_t>(bands * bands));
  for (auto _ : state) {
    std::fill(sums.begin(), sums.end(), T(0));
    if (path == Path::kFast) {
      sh::eval_accumulate(bands, count, d.x.data(), d.y.data(), d.z.data(), weight.data(), sums.data());
    } else {
      sh::detail::eval_accumulate_generic(bands, count, d.x.data(), d.y.data(), d.z.data(), weight.data(), sums.data());
    }
    benchmark::DoNotOptimize(sums.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * count));
  state.counters["dirs"] = static_cast<double>(count);
}

// sh::Accumulator fed `call` directions per add, `total` directions in all, then its totals: the
// fused path for short calls (the partial sums stay in the object between calls, reduced once).
template <typename T>
void bench_stream(benchmark::State& state, int bands, std::size_t call, std::size_t total) {
  Directions<T> d = random_directions<T>(total);
  std::vector<T> weight(total);
  for (std::size_t j = 0; j < total; ++j) weight[j] = static_cast<T>(0.5 + 0.25 * d.x[j]);
  std::vector<T> sums(static_cast<std::size_t>(bands * bands));
  sh::Accumulator<T> acc(bands);
  for (auto _ : state) {
    acc.clear();
    for (std::size_t j = 0; j < total; j += call) {
      const std::size_t n = std::min(call, total - j);
      acc.add(n, d.x.data() + j, d.y.data() + j, d.z.data() + j, weight.data() + j);
    }
    std::fill(sums.begin(), sums.end(), T(0));
    acc.add_to(sums.data());
    benchmark::DoNotOptimize(sums.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * total));
  state.counters["dirs"] = static_cast<double>(total);
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
      auto ratio = run.counters.find("ratio");
      if (ratio != run.counters.end()) samples_[run.run_name.function_name].push_back(ratio->second.value);
      auto dirs = run.counters.find("dirs");
      if (dirs == run.counters.end()) continue;
      double ns = run.cpu_accumulated_time * 1e9 / (static_cast<double>(run.iterations) * dirs->second.value);
      samples_[run.run_name.function_name].push_back(ns);
    }
  }

  /// Median ns per direction of a benchmark (its "ratio" counter where it has one), or NAN if it did not run
  /// (filtered out).
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

// The issue's targets (float, batched, ns per direction) and Sloan's SSE x4 figures, where given.
double target_ns(int bands) { return bands == 3 ? 0.6 : bands == 5 ? 1.6 : bands == 9 ? 6.0 : NAN; }
double sloan_sse_ns(int bands) {
  return bands == 3 ? 0.61 : bands == 5 ? 1.58 : bands == 7 ? 3.35 : bands == 9 ? 6.0 : NAN;
}
// Sloan's scalar code, one direction (float), from the same table.
double sloan_scalar_ns(int bands) {
  return bands == 3 ? 2.1 : bands == 5 ? 6.4 : bands == 7 ? 13.6 : bands == 9 ? 23.2 : NAN;
}

// Directions per call of the fused benchmarks: short calls (16 and 64 directions, where the per-call cost of
// the bands^2 accumulators shows), 256, the batch, and one far beyond L2.
std::vector<std::size_t> fused_counts(std::size_t batch) {
  std::vector<std::size_t> counts = {16, 64, 256, batch, 65536};
  std::sort(counts.begin(), counts.end());
  counts.erase(std::unique(counts.begin(), counts.end()), counts.end());
  return counts;
}

std::string fused_kind(std::size_t count) { return "fused_dirs=" + std::to_string(count); }

// Directions per add call of the sh::Accumulator benchmarks (the batch's directions in all).
const std::vector<std::size_t> kStreamCalls = {16, 64};
std::string stream_kind(std::size_t call) { return "stream_dirs=" + std::to_string(call); }

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
  std::printf("%5s %5s | %-36s | %-23s | %-26s | %-22s | %-15s | %-17s | %-30s | %-22s\n", "bands", "coefs",
              "float batch ns/dir ns/coef  target", "stride=count /padded", "write bound ns  B/dir  GB/s",
              "s=c bound: rows  tiled",
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
    double fill_count = r.median(name_of("fill_stride=count", "float", Path::kFast, bands));
    double fill_tiled = r.median(name_of("fill_tiled_stride=count", "float", Path::kFast, bands));
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
    std::printf("%5d %5d | %7.3f %8.4f  %-14s | %7.3f %5.2fx %-8s | %7.3f %6.0f %7.1f   | %7.3f %4zu %7.3f | %7.3f %6.2fx | %7.3f %8.4f | "
                "%7.2f %7.2f %5.2fx %-7s | %7.2f %7.2f %5.2fx\n",
                bands, bands * bands, ff, ff / n2, target, fc, fc / ff, fc <= 1.05 * ff ? "ok" : "SLOWER", fill,
                n2 * sizeof(float), n2 * sizeof(float) / fill, fill_count, sh::detail::staged_tile_directions(bands, batch, sizeof(float)),
                fill_tiled, fg, fg / ff, df, df / n2, of, og, og / of, scalar_peer,
                odf, odg, odg / odf);
  }
  std::printf("targets (float, batched, per direction): 3 bands <= 0.6 ns, 5 <= 1.6 ns, 9 <= 6 ns; ns/coef flat "
              "up to 16 bands.\n'stride=count /padded': the batch with out_stride = count, and its ratio to the padded "
              "figure ('ok' within 5%%). 'write bound': std::fill of the same output bytes (bands^2 x 4 B per "
              "direction, shown) in the padded layout, measured in this run, and the write bandwidth it reaches: a "
              "batch cannot beat it; where the output outgrows the L1 data cache (bands^2 x 4 B x %zu directions) the "
              "batch figure is that bound plus a little, and the targets are bounds on memory, not on evaluation.\n"
              "'s=c bound': std::fill of the same bytes with out_stride = count, whole rows one after another ('rows'), "
              "and in the order of eval_batch's path for crowded strides ('tiled': tiles of the shown number of "
              "directions, 4 rows at a time, a vector of directions into each in turn, where it runs pieces; one "
              "row's run of the tile at a time where it runs column tiles): that path cannot beat 'tiled'.\n"
              "Peer figures in parentheses are CONSTANTS (Sloan, JCGT 2013, SSE x4 0.61 / 1.58 / 3.35 / 6.0 ns and "
              "scalar 2.1 / 6.4 / 13.6 / 23.2 ns for 3 / 5 / 7 / 9 bands, measured once on this machine kind), not "
              "measured in this run.\n", batch);
}

// Page offsets (bytes) of the inputs in the 'placed' benchmarks: spread over the page, and 128 bytes below
// the rows' offset, where the inputs' loads meet the rows' stores most.
const std::vector<std::size_t> kInputOffsets = {0, 1024, 2048, 3072, 3968};
std::string placed_kind(std::size_t offset) { return "placed_ratio_in@" + std::to_string(offset); }

void print_placed_table(const SummaryReporter& r, std::size_t batch) {
  std::printf("\nstride = count against padded with the inputs placed (rows on a page boundary; x, y, z at the "
              "page offset shown, bytes), float, %zu directions: the median of paired time ratios, and the worst "
              "('ok' within 5%%):\n", batch);
  std::printf("%5s |", "bands");
  for (std::size_t offset : kInputOffsets) std::printf(" in@%-5zu|", offset);
  std::printf(" worst\n");
  for (int bands = 1; bands <= sh::kMaxBands; ++bands) {
    double worst = 0.0;
    bool any = false;
    for (std::size_t offset : kInputOffsets)
      any = any || !std::isnan(r.median(name_of(placed_kind(offset).c_str(), "float", Path::kFast, bands)));
    if (!any) continue;
    std::printf("%5d |", bands);
    for (std::size_t offset : kInputOffsets) {
      const double ratio = r.median(name_of(placed_kind(offset).c_str(), "float", Path::kFast, bands));
      std::printf(" %6.2fx |", ratio);
      if (ratio > worst) worst = ratio;
    }
    std::printf(" %5.2fx %s\n", worst, worst <= 1.05 ? "ok" : "SLOWER");
  }
}

// The header of a table whose columns are direction counts.
void print_count_header(const std::vector<std::size_t>& counts) {
  std::printf("%5s |", "bands");
  for (std::size_t count : counts) std::printf(" %7zu dirs      |", count);
}

// One row's cells: the float fast-path median of kind(count) for each count, with the target verdict.
template <typename Kind>
void print_count_cells(const SummaryReporter& r, int bands, const std::vector<std::size_t>& counts, Kind kind) {
  const double t = target_ns(bands);
  std::printf("%5d |", bands);
  for (std::size_t count : counts) {
    double v = r.median(name_of(kind(count).c_str(), "float", Path::kFast, bands));
    char target[32] = "";
    if (!std::isnan(t)) std::snprintf(target, sizeof target, "<=%.1f %s", t, verdict(v, t).c_str());
    std::printf(" %7.3f %-9s |", v, target);
  }
}

void print_fused_table(const SummaryReporter& r, std::size_t batch) {
  const std::vector<std::size_t> counts = fused_counts(batch);
  std::printf("\nFused evaluate-and-accumulate (sh::eval_accumulate: sums[k] += sum_j w_j Y_k(d_j), nothing per "
              "direction stored; 16 B per direction read), float, CPU ns per direction, one call per batch of:\n");
  print_count_header(counts);
  std::printf(" generic (%zu)    x\n", batch);
  for (int bands = 1; bands <= sh::kMaxBands; ++bands) {
    double fast_batch = r.median(name_of(fused_kind(batch).c_str(), "float", Path::kFast, bands));
    double generic = r.median(name_of(fused_kind(batch).c_str(), "float", Path::kGeneric, bands));
    if (std::isnan(fast_batch) && std::isnan(generic)) continue;
    print_count_cells(r, bands, counts, fused_kind);
    std::printf(" %7.3f %6.2fx\n", generic, generic / fast_batch);
  }
  std::printf("input bandwidth at the largest count: 16 B per direction / ns per direction (the inputs of 65536 "
              "directions, 1 MiB, come from L3).\n");
  std::printf("\nsh::Accumulator (partial sums kept between calls, reduced once), %zu directions in calls of:\n", batch);
  print_count_header(kStreamCalls);
  std::printf("\n");
  for (int bands = 1; bands <= sh::kMaxBands; ++bands) {
    if (std::isnan(r.median(name_of(stream_kind(kStreamCalls[0]).c_str(), "float", Path::kFast, bands)))) continue;
    print_count_cells(r, bands, kStreamCalls, stream_kind);
    std::printf("\n");
  }
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
        add(name_of("fill_stride=count", "float", path, bands),
            [=](benchmark::State& s) { bench_fill<float>(s, bands, batch, batch); });
        add(name_of("fill_tiled_stride=count", "float", path, bands),
            [=](benchmark::State& s) { bench_fill_tiled<float>(s, bands, batch, batch); });
        for (std::size_t offset : kInputOffsets) {
          if (bands < 2) break;
          add(name_of(placed_kind(offset).c_str(), "float", path, bands),
              [=](benchmark::State& s) { bench_placed_ratio(s, bands, batch, offset); });
        }
      }
      for (std::size_t count : fused_counts(batch)) {
        if (path == Path::kGeneric && count != batch) continue;  // the generic path at the batch only
        if (path == Path::kGeneric && bands > sh::kMaxFastBands) continue;  // the same code as fast there
        add(name_of(fused_kind(count).c_str(), "float", path, bands),
            [=](benchmark::State& s) { bench_fused<float>(s, bands, path, count); });
      }
      if (path == Path::kFast)
        for (std::size_t call : kStreamCalls)
          add(name_of(stream_kind(call).c_str(), "float", path, bands),
              [=](benchmark::State& s) { bench_stream<float>(s, bands, call, batch); });
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
  print_placed_table(reporter, batch);
  print_fused_table(reporter, batch);
  benchmark::Shutdown();
  return 0;
}
