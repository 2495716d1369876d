// Textures per pixel (issue 33, the albedo split): frame time of a per-vertex diffuse transfer on a
// textured mesh shown with its texture (albedo-free draw, then the deferred base-colour pass,
// render/base_colour.h) against the same transfer drawn without it (the untextured path, unchanged), on
// the same mesh, camera and bands, alternating frame by frame. Headless (EGL); on llvmpipe the times are
// a CPU rasteriser's, so the figure to read is the textured / untextured ratio of the same run.
#include <benchmark/benchmark.h>

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

// A floor of n x n quads over [-1, 1]^2 (y = 0) with one material: a size^2 pattern repeated twice
// across the floor (bilinear, repeat), per-corner UVs, a grey per-vertex albedo.
mesh::Mesh textured_floor(int n, int size) {
  std::vector<glm::vec2> uv;
  mesh::Mesh m = bench::floor_grid(n, &uv, 2.0f);
  m.base_color_uv = uv;
  m.albedo.assign(m.vertex_count(), glm::vec3(0.5f));
  m.triangle_material.assign(m.triangle_count(), 0u);
  mesh::Material material;
  material.base_color.image = 0;
  m.materials.push_back(material);
  mesh::Texture texture;
  texture.width = texture.height = size;
  texture.rgb.resize(3 * static_cast<std::size_t>(size) * size);
  for (std::size_t i = 0; i < texture.rgb.size(); ++i) texture.rgb[i] = 0.01f * static_cast<float>((i * 7919) % 97);
  m.textures.push_back(texture);
  m.albedo_source = mesh::AlbedoSource::texture;
  return m;
}

std::map<int, bench::FramePair> results;  // per texture size: textured (a), untextured (b)

void frame_textured_vs_untextured(benchmark::State& state, render::Renderer& renderer, int size) {
  const mesh::Mesh mesh = textured_floor(64, size);
  renderer.set_mesh(mesh);
  const transfer::TransferData data = bench::synthetic_diffuse(mesh);
  const int textured = renderer.add_transfer(data, "synthetic");
  renderer.set_textured(textured, true);
  const int plain = renderer.add_transfer(data, "synthetic");
  renderer.set_lighting(bench::synthetic_lighting(5), nullptr);
  const render::Camera camera{30.0, 40.0, 0.0};
  const bench::FramePair times = bench::alternate_frames(state, renderer, bench::black_frame(textured, camera),
                                                         bench::black_frame(plain, camera), kFrameSize);
  results[size] = times;
  state.counters["textured_ms"] = times.a_ms;
  state.counters["untextured_ms"] = times.b_ms;
  state.counters["textured/untextured"] = times.a_ms / times.b_ms;
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  render::HeadlessContext context;
  std::printf("bench_render_texture: %s; frames %dx%d, 5 bands RGB\n", context.description().c_str(), kFrameSize, kFrameSize);
  render::Renderer renderer;
  for (int size : {256, 1024}) {
    const std::string name = "frame_textured_vs_untextured/texture:" + std::to_string(size);
    benchmark::RegisterBenchmark(name.c_str(), [&renderer, size](benchmark::State& state) {
      frame_textured_vs_untextured(state, renderer, size);
    })->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(2.0);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  std::printf("\nSummary (floor of 8192 triangles filling most of the frame, the texture repeated twice across it)\n");
  for (const auto& [size, r] : results)
    std::printf("texture %4dx%-4d  textured %7.2f ms  untextured %7.2f ms  ratio %.3f\n", size, size, r.a_ms, r.b_ms, r.a_ms / r.b_ms);
  return 0;
}
