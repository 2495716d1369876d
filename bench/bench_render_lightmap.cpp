// Lightmap rendering (issue 12): frame time of a texel transfer sampled per pixel (renderer_lightmap.h)
// against the per-vertex diffuse pass on the same mesh, camera and bands, alternating frame by frame,
// and the one-time upload of the texture arrays. Headless (EGL); on llvmpipe the absolute times are a
// CPU rasteriser's, so the figure to read is the lightmap / per-vertex ratio measured in the same run.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>
#include <map>
#include <string>

#include "bench_frames.h"
#include "bench_lighting.h"
#include "mesh/mesh.h"
#include "render/gl.h"
#include "render/headless_context.h"
#include "render/renderer.h"

using namespace prt;

namespace {

constexpr int kFrameSize = 1024;
using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// A floor of n x n quads over [-1, 1]^2 (y = 0), one lightmap chart: uv = ((x + 1) / 2, (z + 1) / 2).
mesh::Mesh floor_grid(int n) {
  std::vector<glm::vec2> uv;
  mesh::Mesh m = bench::floor_grid(n, &uv);
  m.lightmap_uv = uv;
  return m;
}

struct Result {
  double lightmap_ms = 0.0, vertex_ms = 0.0, upload_ms = 0.0, megabytes = 0.0;
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  render::HeadlessContext context;
  std::printf("bench_render_lightmap: %s; frames %dx%d, 5 bands RGB\n", context.description().c_str(), kFrameSize, kFrameSize);
  render::Renderer renderer;
  std::map<int, Result> results;
  for (int texels : {256, 512}) {
    const std::string name = "frame_lightmap_vs_vertex/lightmap:" + std::to_string(texels) + "/" + std::to_string(kFrameSize);
    benchmark::RegisterBenchmark(name.c_str(), [&renderer, &results, texels](benchmark::State& state) {
      const mesh::Mesh mesh = floor_grid(64);
      renderer.set_mesh(mesh);
      const transfer::TransferData lightmap_data = bench::synthetic_diffuse(mesh, texels);
      Result& r = results[texels];
      auto start = Clock::now();
      const int lightmap = renderer.add_lightmap(lightmap_data, "synthetic");
      glFinish();
      r.upload_ms = 1e3 * seconds_since(start);
      r.megabytes = static_cast<double>(texels) * texels * 19 * 16 * 1e-6;
      const int vertex = renderer.add_transfer(bench::synthetic_diffuse(mesh), "synthetic");
      renderer.set_lighting(bench::synthetic_lighting(5), nullptr);
      const render::Camera camera{30.0, 40.0, 0.0};
      const render::FrameSettings a = bench::black_frame(lightmap, camera), b = bench::black_frame(vertex, camera);
      const bench::FramePair times = bench::alternate_frames(state, renderer, a, b, kFrameSize);
      r.lightmap_ms = times.a_ms;
      r.vertex_ms = times.b_ms;
      state.counters["lightmap_ms"] = r.lightmap_ms;
      state.counters["vertex_ms"] = r.vertex_ms;
      state.counters["lightmap/vertex"] = r.lightmap_ms / r.vertex_ms;
    })->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(2.0);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  std::printf("\nSummary (floor of 8192 triangles filling most of a %dx%d frame, 5 bands RGB, 19 RGBA32F layers)\n",
              kFrameSize, kFrameSize);
  std::printf("%-10s %12s %12s %16s %12s %10s\n", "lightmap", "lightmap ms", "vertex ms", "lightmap/vertex", "upload ms", "level-0 MB");
  for (const auto& [texels, r] : results)
    std::printf("%4dx%-5d %12.2f %12.2f %16.2f %12.1f %10.1f\n", texels, texels, r.lightmap_ms, r.vertex_ms, r.lightmap_ms / r.vertex_ms,
                r.upload_ms, r.megabytes);
  return 0;
}
