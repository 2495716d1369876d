// The reference path tracer's speed (src/reference): paths and rays per second on a ~10k-vertex
// Cornell-like box, direct (--bounces 0) and with 2 bounces, against the bare Embree occlusion pass over
// the same mesh measured in the same run (the physical limit for its rays). The issue sets no target
// for the reference; its default --samples is chosen so that the default run (direct, 10k vertices)
// takes about a minute on 2 cores: each benchmark prints that run's predicted time.
#include <benchmark/benchmark.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "bench_meshes.h"
#include "reference/reference.h"

namespace {

using namespace prt;

// A sky with a gradient and a broad sun lobe, equirect 256 x 128 (the tests' synthetic sky).
light::Environment sky() {
  light::Environment env;
  env.equirect = image::Image(256, 128, 3);
  const glm::dvec3 sun = glm::normalize(glm::dvec3(0.5, 0.8, 0.3));
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 256; ++x) {
      const glm::dvec3 d = light::equirect_direction((x + 0.5) / 256, (y + 0.5) / 128);
      glm::dvec3 v = d.y > 0 ? glm::dvec3(0.3, 0.4, 0.6) * (0.5 + 0.5 * d.y) : glm::dvec3(0.15, 0.12, 0.1);
      v += glm::dvec3(8.0, 7.2, 5.6) * std::exp(30.0 * (glm::dot(d, sun) - 1.0));
      for (int c = 0; c < 3; ++c) env.equirect.at(x, y, c) = static_cast<float>(v[c]);
    }
  return env;
}

void reference_run(benchmark::State& state, int bounces) {
  const mesh::Mesh mesh = bench::cornell_box(45);
  const reference::EnvironmentSampler sampler(sky());
  reference::ReferenceOptions options;
  options.samples = 64;
  options.bounces = bounces;
  options.threads = 2;

  // Baseline: bare Embree occlusion rays from every vertex, same mesh, same threads.
  const trace::Scene scene(mesh);
  const bench::PassResult bare =
      bench::occlusion_pass(scene, mesh, trace::morton_order(mesh.positions), bench::hemisphere_directions(64), 2);

  reference::ReferenceReport report;
  double paths = 0, rays = 0, seconds = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(reference::vertex_radiance(mesh, sampler, options, &report));
    paths += static_cast<double>(report.paths);
    rays += static_cast<double>(report.rays);
    seconds += report.seconds_trace;
  }
  const double paths_per_second = paths / seconds, rays_per_second = rays / seconds;
  state.counters["vertices"] = static_cast<double>(mesh.vertex_count());
  state.counters["Mpaths_per_s"] = paths_per_second / 1e6;
  state.counters["Mrays_per_s"] = rays_per_second / 1e6;
  state.counters["bare_embree_Mrays_per_s"] = bare.mrays_per_second;
  state.counters["rays_vs_bare"] = rays_per_second / 1e6 / bare.mrays_per_second;
  // Predicted time of `prt reference` with the default --samples on 10,000 vertices (target: ~60 s).
  state.counters["default_run_10k_s"] = 1e4 * reference::kDefaultSamples / paths_per_second;
}

void BM_ReferenceDirect(benchmark::State& state) { reference_run(state, 0); }
void BM_ReferenceTwoBounces(benchmark::State& state) { reference_run(state, 2); }

BENCHMARK(BM_ReferenceDirect)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_ReferenceTwoBounces)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
