// Sun/sky split speed (light/sun_extraction.h, light/deringing.h) on a 2048x1024 map: the bundled
// sunrise.exr resampled to that size (bilinear, Environment::radiance), so the sun covers a realistic
// number of texels. Target from the issue: extraction plus deringing (the auto window at 5 bands) in
// <= 50 ms on 2 cores. The projection of the residual, which every shading command does anyway with or
// without the split, is measured beside it as the in-run baseline.
#include <benchmark/benchmark.h>

#include "bench_report.h"

#include <cstdio>
#include <map>
#include <string>

#include "light/deringing.h"
#include "light/environment.h"
#include "light/projection.h"
#include "light/sun_extraction.h"

namespace {

const prt::light::Environment& sunrise_2048() {
  static const prt::light::Environment env = [] {
    const prt::light::Environment source = prt::light::load_environment(std::string(PRT_SOURCE_DIR) + "/assets/env/sunrise.exr");
    prt::light::Environment out;
    out.equirect = prt::image::Image(2048, 1024, 3);
    for (int y = 0; y < 1024; ++y)
      for (int x = 0; x < 2048; ++x) {
        const glm::dvec3 l = source.radiance(prt::light::equirect_direction((x + 0.5) / 2048, (y + 0.5) / 1024));
        for (int c = 0; c < 3; ++c) out.equirect.at(x, y, c) = static_cast<float>(l[c]);
      }
    return out;
  }();
  return env;
}

void BM_Extract(benchmark::State& state) {
  const auto& env = sunrise_2048();
  const int threads = static_cast<int>(state.range(0));
  std::size_t discs = 0;
  for (auto _ : state) {
    auto r = prt::light::extract_discs(env, threads);
    discs = r.discs.size();
    benchmark::DoNotOptimize(r.residual.equirect.pixels.data());
  }
  state.counters["discs"] = static_cast<double>(discs);
}
BENCHMARK(BM_Extract)->ArgName("threads")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_AutoWindow(benchmark::State& state) {
  const int bands = static_cast<int>(state.range(0));
  const prt::sh::RgbCoefficients residual = prt::light::project(prt::light::extract_discs(sunrise_2048(), 2).residual, bands, 2);
  for (auto _ : state) {
    prt::sh::RgbCoefficients c = residual;
    auto choice = prt::light::apply_window_request(prt::light::WindowRequest{}, c);
    benchmark::DoNotOptimize(choice.param);
  }
}
BENCHMARK(BM_AutoWindow)->ArgName("bands")->Arg(3)->Arg(5)->Arg(9)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ProjectResidual(benchmark::State& state) {
  const prt::light::Environment residual = prt::light::extract_discs(sunrise_2048(), 2).residual;
  for (auto _ : state) {
    auto c = prt::light::project(residual, 5, 2);
    benchmark::DoNotOptimize(c.values.data());
  }
}
BENCHMARK(BM_ProjectResidual)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  bench::RecordingReporter reporter;
  if (!bench::run_benchmarks(argc, argv, reporter)) return 1;
  const double extract = bench::lookup(reporter.ms, "BM_Extract/threads:2/real_time");
  const double window = bench::lookup(reporter.ms, "BM_AutoWindow/bands:5/real_time");
  const double project = bench::lookup(reporter.ms, "BM_ProjectResidual/real_time");
  if (extract < 0 || window < 0) return 0;
  std::printf("\nSun/sky split, 2048x1024 sunrise, 2 threads: extraction %.2f ms + auto window (5 bands) %.2f ms = %.2f ms "
              "(target <= 50 ms: %s); projection of the residual to 5 bands %.2f ms (baseline, done with or without the split)\n",
              extract, window, extract + window, extract + window <= 50.0 ? "met" : "MISSED", project);
  return 0;
}
