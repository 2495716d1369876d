// Textures per pixel (issue 33, the albedo split): frame time of a per-vertex diffuse transfer on a
// textured mesh shown with its texture (albedo-free draw, then the deferred base-colour pass,
// render/base_colour.h) against the same transfer drawn without it (the untextured path, unchanged), on
// the same mesh, camera and bands, alternating frame by frame. Headless (EGL); on llvmpipe the times are
// a CPU rasteriser's, so the figure to read is the textured / untextured ratio of the same run.
#include <benchmark/benchmark.h>

#include <cstdio>
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
constexpr int kTextureSize = 1024;

// A floor of n x n quads over [-1, 1]^2 (y = 0) with one material: a kTextureSize^2 pattern repeated
// twice across the floor (bilinear, repeat), per-corner UVs, a grey per-vertex albedo.
mesh::Mesh textured_floor(int n) {
  std::vector<glm::vec2> uv;
  mesh::Mesh m = bench::floor_grid(n, &uv, 2.0f);
  m.base_color_uv = uv;
  m.albedo.assign(m.vertex_count(), glm::vec3(0.5f));
  m.triangle_material.assign(m.triangle_count(), 0u);
  mesh::Material material;
  material.base_color.image = 0;
  m.materials.push_back(material);
  mesh::Texture texture;
  texture.width = texture.height = kTextureSize;
  texture.rgb.resize(3 * static_cast<std::size_t>(kTextureSize) * kTextureSize);
  for (std::size_t i = 0; i < texture.rgb.size(); ++i) texture.rgb[i] = 0.01f * static_cast<float>((i * 7919) % 97);
  m.textures.push_back(texture);
  m.albedo_source = mesh::AlbedoSource::texture;
  return m;
}

double textured_ms = 0.0, untextured_ms = 0.0;

void frame_textured_vs_untextured(benchmark::State& state, render::Renderer& renderer) {
  const mesh::Mesh mesh = textured_floor(64);
  renderer.set_mesh(mesh);
  const transfer::TransferData data = bench::synthetic_diffuse(mesh);
  const int textured = renderer.add_transfer(data, "synthetic");
  renderer.set_textured(textured, true);
  const int plain = renderer.add_transfer(data, "synthetic");
  renderer.set_lighting(bench::synthetic_lighting(5), nullptr);
  const render::Camera camera{30.0, 40.0, 0.0};
  const bench::FramePair times = bench::alternate_frames(state, renderer, bench::black_frame(textured, camera),
                                                         bench::black_frame(plain, camera), kFrameSize);
  textured_ms = times.a_ms;
  untextured_ms = times.b_ms;
  state.counters["textured_ms"] = textured_ms;
  state.counters["untextured_ms"] = untextured_ms;
  state.counters["textured/untextured"] = textured_ms / untextured_ms;
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  render::HeadlessContext context;
  std::printf("bench_render_texture: %s; frames %dx%d, 5 bands RGB, a %dx%d texture\n", context.description().c_str(), kFrameSize,
              kFrameSize, kTextureSize, kTextureSize);
  render::Renderer renderer;
  benchmark::RegisterBenchmark("frame_textured_vs_untextured/1024", [&renderer](benchmark::State& state) {
    frame_textured_vs_untextured(state, renderer);
  })->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(2.0);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  std::printf("\nSummary (floor of 8192 triangles filling most of the frame): textured %.2f ms, untextured %.2f ms, ratio %.3f\n",
              textured_ms, untextured_ms, textured_ms / untextured_ms);
  return 0;
}
