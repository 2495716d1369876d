// Lightmap rendering (issue 12): frame time of a texel transfer sampled per pixel (renderer_lightmap.h)
// against the per-vertex diffuse pass on the same mesh, camera and bands, alternating frame by frame,
// and the one-time upload of the texture arrays. Issue 36: the texel ship default (16 bands, CPCA of
// compress::ship_texel_compression, drawn compressed: render/pass_lightmap_cpca.cpp) against the old
// 5-band lightmap, alternating, with the sky turned every frame (the compressed pass reshades its
// texels on every lighting change) and with a still sky (it reuses them). Headless (EGL); on llvmpipe the absolute times are a
// CPU rasteriser's, so the figure to read is the lightmap / per-vertex ratio measured in the same run.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>
#include <map>
#include <string>

#include "bench_frames.h"
#include "bench_lighting.h"
#include "compress/compressed.h"
#include "compress/ship_defaults.h"
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

// A texels^2 CPCA model of 16-band RGB shadowed transfer over `mesh`, every texel covered, with the ship
// default's K and N; the values, a fixed pattern, do not change the cost.
compress::CompressedTransfer synthetic_texel_model(const mesh::Mesh& mesh, int texels) {
  compress::CompressedTransfer c;
  c.source.kind = transfer::Kind::shadowed;
  c.source.bands = compress::kHighBands;
  c.source.channels = 3;
  c.source.scalar = transfer::Scalar::float16;
  c.source.vertex_count = mesh.vertex_count();
  c.source.triangle_count = mesh.triangle_count();
  c.source.texel_width = c.source.texel_height = static_cast<std::uint32_t>(texels);
  const std::uint64_t points = c.source.block_count();
  const compress::ShipCompression ship = compress::ship_texel_compression(points, points, 3, 1, compress::kHighBands);
  c.clusters = ship.clusters;
  c.pca = ship.pca;
  c.texel_points = points;
  c.coverage.assign(points, transfer::kTexelCovered);
  c.means.resize(static_cast<std::size_t>(c.clusters) * c.point_dimension());
  c.bases.resize(c.means.size() * static_cast<std::size_t>(c.pca));
  c.weights.resize(points * static_cast<std::size_t>(c.pca));
  c.cluster.resize(points);
  for (std::size_t i = 0; i < c.means.size(); ++i) c.means[i] = 0.01f * static_cast<float>((i * 7919) % 97);
  for (std::size_t i = 0; i < c.bases.size(); ++i) c.bases[i] = 0.001f * static_cast<float>((i * 104729) % 89);
  for (std::size_t i = 0; i < c.weights.size(); ++i) c.weights[i] = 0.01f * static_cast<float>((i * 31) % 53) - 0.2f;
  for (std::size_t p = 0; p < points; ++p) c.cluster[p] = static_cast<std::uint32_t>((p / 4096) % static_cast<std::size_t>(c.clusters));
  return c;
}

struct ShipResult {
  double compressed_ms = 0.0, lightmap_ms = 0.0;
  int clusters = 0, pca = 0;
};

// Registers the texel ship default against the 5-band lightmap at each size, sky turning or still.
void register_ship_default(render::Renderer& renderer, std::map<std::pair<int, bool>, ShipResult>& results) {
  for (int texels : {256, 512})
    for (bool turn : {true, false}) {
      const std::string name = "frame_ship_default_vs_5_band_lightmap/lightmap:" + std::to_string(texels) + (turn ? "/turning" : "/still");
      benchmark::RegisterBenchmark(name.c_str(), [&renderer, &results, texels, turn](benchmark::State& state) {
        const mesh::Mesh mesh = floor_grid(64);
        renderer.set_mesh(mesh);
        const compress::CompressedTransfer model = synthetic_texel_model(mesh, texels);
        const int compressed = renderer.add_compressed(model, "synthetic");
        const int lightmap = renderer.add_lightmap(bench::synthetic_diffuse(mesh, texels), "synthetic");
        renderer.set_lighting(bench::synthetic_lighting(compress::kHighBands), nullptr);
        const render::Camera camera{30.0, 40.0, 0.0};
        const bench::FramePair times =
            bench::alternate_frames(state, renderer, bench::black_frame(compressed, camera), bench::black_frame(lightmap, camera), kFrameSize, turn);
        results[{texels, turn}] = {times.a_ms, times.b_ms, model.clusters, model.pca};
        state.counters["compressed_ms"] = times.a_ms;
        state.counters["lightmap5_ms"] = times.b_ms;
        state.counters["compressed/lightmap5"] = times.a_ms / times.b_ms;
      })->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(2.0);
    }
}

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
  std::map<std::pair<int, bool>, ShipResult> ship;
  register_ship_default(renderer, ship);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  std::printf("\nSummary (floor of 8192 triangles filling most of a %dx%d frame, 5 bands RGB, 19 RGBA32F layers)\n",
              kFrameSize, kFrameSize);
  std::printf("%-10s %12s %12s %16s %12s %10s\n", "lightmap", "lightmap ms", "vertex ms", "lightmap/vertex", "upload ms", "level-0 MB");
  for (const auto& [texels, r] : results)
    std::printf("%4dx%-5d %12.2f %12.2f %16.2f %12.1f %10.1f\n", texels, texels, r.lightmap_ms, r.vertex_ms, r.lightmap_ms / r.vertex_ms,
                r.upload_ms, r.megabytes);
  std::printf("\nTexel ship default (16 bands RGB, CPCA K x N, drawn compressed) vs the 5-band lightmap, same frames\n");
  std::printf("%-10s %8s %-9s %14s %14s %10s\n", "lightmap", "K x N", "sky", "compressed ms", "5-band ms", "ratio");
  for (const auto& [key, r] : ship)
    std::printf("%4dx%-5d %3dx%-4d %-9s %14.2f %14.2f %10.2f\n", key.first, key.first, r.clusters, r.pca, key.second ? "turning" : "still",
                r.compressed_ms, r.lightmap_ms, r.compressed_ms / r.lightmap_ms);
  return 0;
}
