// Irradiance at one normal from RGB radiance coefficients: sh::irradiance (closed-form polynomial for
// bands <= 3, basis evaluation + per-band dot beyond), against the generic path (sh::eval + the
// A_l-weighted dot) measured in the same run. Also the one-off costs of the other zonal/window/
// sampling helpers, for scale. Prints Google Benchmark's table, then a summary with ns per normal next
// to the anchor (eval + dot 7-8 ns for 9 RGB coefficients; google's RenderDiffuseIrradiance
// 529 ns). CPU time per normal; the machine is shared and noisy.
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <glm/geometric.hpp>

#include "light/analytic.h"
#include "sh/basis.h"
#include "sh/coefficients.h"
#include "sh/quadrature.h"
#include "sh/sampling.h"
#include "sh/window.h"
#include "sh/zonal.h"
#include "support/random_draws.h"

namespace sh = prt::sh;

namespace {

constexpr std::size_t kNormals = 1024;

std::vector<glm::dvec3> random_normals() {
  std::mt19937_64 rng(42);
  std::vector<glm::dvec3> out;
  for (std::size_t i = 0; i < kNormals; ++i) out.push_back(prt::test::random_direction(rng));
  return out;
}

sh::RgbCoefficients random_radiance(int bands) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> n;
  sh::RgbCoefficients c(bands);
  for (auto& v : c.values) v = prt::test::draw_vec3<double>(rng, n);
  return c;
}

// Result figures for the summary: name -> ns per normal.
std::map<std::string, double>& figures() {
  static std::map<std::string, double> f;
  return f;
}

void count_normals(benchmark::State& state) {
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kNormals));
}

void BM_irradiance(benchmark::State& state) {
  const int bands = static_cast<int>(state.range(0));
  const auto normals = random_normals();
  const sh::RgbCoefficients radiance = random_radiance(bands);
  for (auto _ : state) {
    glm::dvec3 sum(0.0);
    for (const glm::dvec3& n : normals) sum += sh::irradiance(radiance, n);
    benchmark::DoNotOptimize(sum);
  }
  count_normals(state);
}

// Baseline: evaluate all bands^2 basis functions, then sum A_l L_lm Y_lm.
void BM_eval_dot(benchmark::State& state) {
  const int bands = static_cast<int>(state.range(0));
  const auto normals = random_normals();
  const sh::RgbCoefficients radiance = random_radiance(bands);
  std::vector<double> a(static_cast<std::size_t>(bands * bands));
  for (int i = 0; i < bands * bands; ++i) a[i] = sh::clamped_cosine_factor(sh::band_of(i));
  double y[sh::kMaxBands * sh::kMaxBands];
  for (auto _ : state) {
    glm::dvec3 sum(0.0);
    for (const glm::dvec3& n : normals) {
      sh::eval(bands, n, y);
      glm::dvec3 e(0.0);
      for (int i = 0; i < bands * bands; ++i) e += (a[i] * y[i]) * radiance.values[i];
      sum += e;
    }
    benchmark::DoNotOptimize(sum);
  }
  count_normals(state);
}

void BM_nonnegative_lambda(benchmark::State& state) {
  const int bands = static_cast<int>(state.range(0));
  const sh::RgbCoefficients light = prt::light::directional_light(bands, {0.3, 0.8, 0.1}, glm::dvec3(1.0));
  std::vector<double> c(static_cast<std::size_t>(bands * bands));
  for (int i = 0; i < bands * bands; ++i) c[i] = light.values[i].x;
  for (auto _ : state) benchmark::DoNotOptimize(sh::nonnegative_laplacian_lambda(bands, c.data()));
}

void BM_sphere_directions_4096(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(sh::sphere_directions(4096, 1));
}

void BM_product_quadrature(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(sh::gauss_product_quadrature(static_cast<int>(state.range(0))));
}

void BM_cone_light(benchmark::State& state) {
  const int bands = static_cast<int>(state.range(0));
  for (auto _ : state)
    benchmark::DoNotOptimize(prt::light::cone_light(bands, {0.3, 0.8, 0.1}, 0.2, glm::dvec3(1.0)));
}

// Collects the median CPU time per item of the repeated irradiance benchmarks.
class SummaryReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& r : runs) {
      if (r.run_type != Run::RT_Aggregate || r.aggregate_name != "median") continue;
      const double ns = r.GetAdjustedCPUTime() / kNormals;  // time unit is ns by default
      figures()[r.benchmark_name()] = ns;
    }
  }
};

}  // namespace

BENCHMARK(BM_irradiance)->Arg(1)->Arg(2)->Arg(3)->Arg(4)->Arg(5)->Arg(9)->Repetitions(5);
BENCHMARK(BM_eval_dot)->Arg(3)->Arg(4)->Arg(5)->Arg(9)->Repetitions(5);
BENCHMARK(BM_nonnegative_lambda)->Arg(3)->Arg(9)->Arg(16)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_sphere_directions_4096)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_product_quadrature)->Arg(30)->Arg(62)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_cone_light)->Arg(3)->Arg(9)->Unit(benchmark::kMicrosecond);

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  SummaryReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  std::printf("\nIrradiance at one normal (ns per normal, median CPU time; anchor: eval + dot 7-8 ns for\n"
              "9 RGB coefficients, google RenderDiffuseIrradiance 529 ns):\n");
  for (int bands : {3, 4, 5, 9}) {
    const std::string fast = "BM_irradiance/" + std::to_string(bands) + "/repeats:5_median";
    const std::string base = "BM_eval_dot/" + std::to_string(bands) + "/repeats:5_median";
    if (!figures().count(fast) || !figures().count(base)) continue;
    std::printf("  bands %d (%2d RGB coefficients): sh::irradiance %6.2f ns, eval + dot baseline %6.2f ns, "
                "ratio %.2fx%s\n",
                bands, bands * bands, figures()[fast], figures()[base], figures()[base] / figures()[fast],
                bands == 3 ? "   (target 7-8 ns)" : "");
  }
  return 0;
}
