// bench_probes: SH light probe baking (src/probes) against a bare Embree pass over the same rays.
//
// Scene: bench::cornell_box(100) (a room open at +Z with two blocks; 100k+ triangles), lit by
// assets/env/sunrise.exr and a sun. Probes: a 32 x 8 x 32 grid (8192 probes) over the room's bounds,
// 3 bands, 1024 rays per probe, 2 bounces, 256 surface samples per vertex, 2 threads.
// Figures (issue 6): probes per second of the probe pass and its ratio to the bare Embree pass
// (target <= 1.3); wall time of the whole 32x8x32 bake on 2 cores (surface light + probes).
// The bare pass traces the same number of rays per probe (the same sphere set, each probe's set turned
// by a hashed rotation) with Scene::intersect in batches of 1024 and does nothing with the hits.
// CPU seconds (all threads of the process) are printed too: they stay meaningful on a busy machine.
// Three interleaved rounds of each; the summary uses the fastest of each.
#include <sys/resource.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include <benchmark/benchmark.h>
#include <glm/gtc/quaternion.hpp>

#include "bench_meshes.h"
#include "core/parallel.h"
#include "light/environment.h"
#include "probes/baker.h"
#include "probes/surface.h"
#include "sh/sampling.h"
#include "trace/scene.h"

using namespace prt;

namespace {

constexpr double kTargetRatio = 1.3;
constexpr int kThreads = 2;

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

struct Fixture {
  mesh::Mesh mesh;
  light::Environment environment;
  std::vector<glm::dvec3> positions;
  probes::ProbeSet layout;
  double probe_seconds = 0, probe_cpu = 0, bake_seconds = 0, surface_seconds = 0, bare_seconds = 0, bare_cpu = 0;
  std::size_t invalid = 0;
};

// Keeps the fastest of the interleaved runs (0 = none yet); true if `value` is the new best.
bool keep_best(double& best, double value) {
  if (best > 0.0 && best <= value) return false;
  best = value;
  return true;
}

Fixture& fixture() {
  static std::unique_ptr<Fixture> f;
  if (!f) {
    f = std::make_unique<Fixture>();
    f->mesh = bench::cornell_box(100);
    f->mesh.positions.reserve(f->mesh.positions.size() + 1);
    f->environment = light::load_environment(std::string(PRT_SOURCE_DIR) + "/assets/env/sunrise.exr");
    f->layout.layout = probes::ProbeSet::Layout::grid;
    f->layout.grid.counts = {{32, 8, 32}};
    f->layout.grid.lo = {0.0, 0.0, 0.0};
    f->layout.grid.hi = {1.0, 1.0, 1.0};
    f->positions = probes::grid_positions(f->layout.grid);
  }
  return *f;
}

void BM_ProbeBake(benchmark::State& state) {
  Fixture& f = fixture();
  probes::SceneLight light;
  light.environment = &f.environment;
  light.sun = probes::parse_sun("0.3,1,0.6,5,0.5");
  probes::ProbeBakeOptions options;
  options.threads = kThreads;
  for (auto _ : state) {
    probes::ProbeBakeReport report;
    const double cpu0 = cpu_seconds();
    const auto start = std::chrono::steady_clock::now();
    const probes::ProbeSet set = probes::bake_probes(f.mesh, light, f.positions, f.layout, options, &report);
    const double bake_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    (void)cpu0;
    keep_best(f.probe_seconds, report.seconds_probes);
    keep_best(f.probe_cpu, report.cpu_seconds_probes);
    if (keep_best(f.bake_seconds, bake_seconds)) f.surface_seconds = report.seconds_surface;
    f.invalid = report.invalid;
    benchmark::DoNotOptimize(set.coefficients.data());
  }
  state.counters["triangles"] = static_cast<double>(f.mesh.triangle_count());
  state.counters["probes_per_s"] = f.positions.size() / f.probe_seconds;
  state.counters["bake_wall_s"] = f.bake_seconds;
  state.counters["surface_s"] = f.surface_seconds;
  state.counters["probe_pass_s"] = f.probe_seconds;
}

void BM_BareEmbree(benchmark::State& state) {
  Fixture& f = fixture();
  const trace::Scene scene(f.mesh, trace::SceneOptions{kThreads});
  std::vector<glm::vec3> directions;
  for (const glm::dvec3& d : sh::sphere_directions(1024, 1)) directions.emplace_back(d);
  for (auto _ : state) {
    std::atomic<std::size_t> hits{0};
    const double cpu0 = cpu_seconds();
    const auto start = std::chrono::steady_clock::now();
    parallel_for(f.positions.size(), 8, kThreads, [&](std::size_t begin, std::size_t end) {
      trace::RayBatch batch(1024);
      std::size_t local = 0;
      for (std::size_t p = begin; p < end; ++p) {
        const double u1 = probes::hash_to_unit(1, p, 1), u2 = probes::hash_to_unit(1, p, 2), u3 = probes::hash_to_unit(1, p, 3);
        const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1), tau = 6.283185307179586;
        const glm::mat3 r(glm::mat3_cast(glm::dquat(b * std::cos(tau * u3), a * std::sin(tau * u2), a * std::cos(tau * u2), b * std::sin(tau * u3))));
        const glm::vec3 origin(f.positions[p]);
        batch.clear();
        for (const glm::vec3& d : directions) batch.push(origin, r * d);
        scene.intersect(batch);
        for (std::size_t i = 0; i < batch.size(); ++i) local += batch.data()[i].hit.prim_id != trace::kNoHit;
      }
      hits += local;
    });
    keep_best(f.bare_seconds, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    keep_best(f.bare_cpu, cpu_seconds() - cpu0);
    benchmark::DoNotOptimize(hits.load());
  }
  state.counters["probes_per_s"] = f.positions.size() / f.bare_seconds;
  state.counters["Mrays_per_s"] = f.positions.size() * 1024.0 / f.bare_seconds / 1e6;
}

// Three interleaved rounds; the summary compares the fastest run of each (the machine is shared).
BENCHMARK(BM_BareEmbree)->Name("BM_BareEmbree/round1")->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ProbeBake)->Name("BM_ProbeBake/round1")->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_BareEmbree)->Name("BM_BareEmbree/round2")->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ProbeBake)->Name("BM_ProbeBake/round2")->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_BareEmbree)->Name("BM_BareEmbree/round3")->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ProbeBake)->Name("BM_ProbeBake/round3")->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  Fixture& f = fixture();
  if (f.probe_seconds > 0 && f.bare_seconds > 0) {
    std::printf("\nbench_probes summary (%zu triangles, %zu probes, 3 bands, 1024 rays, %d threads; %zu invalid)\n",
                f.mesh.triangle_count(), f.positions.size(), kThreads, f.invalid);
    std::printf("  probe pass:           %8.0f probes/s  (%.3f s wall, %.3f s CPU)\n", f.positions.size() / f.probe_seconds,
                f.probe_seconds, f.probe_cpu);
    std::printf("  bare Embree, same rays: %6.0f probes/s  (%.3f s wall, %.3f s CPU)\n", f.positions.size() / f.bare_seconds,
                f.bare_seconds, f.bare_cpu);
    std::printf("  ratio probe pass / bare Embree: %.2f wall, %.2f CPU (target <= %.1f)\n", f.probe_seconds / f.bare_seconds,
                f.probe_cpu / f.bare_cpu, kTargetRatio);
    std::printf("  32x8x32 grid, whole bake on %d cores: %.2f s wall (surface light %.2f s, probes %.2f s)\n", kThreads,
                f.bake_seconds, f.surface_seconds, f.probe_seconds);
  }
  benchmark::Shutdown();
  return 0;
}
