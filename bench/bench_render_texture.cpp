// Textures per pixel (issue 33, the albedo split): frame time of a per-vertex diffuse transfer on a
// textured mesh shown with its texture (albedo-free radiance per vertex times the base colour per pixel,
// one indexed draw: render/base_colour.h) against the same transfer drawn without it (the untextured
// path), on the same mesh, camera and bands, alternating frame by frame. Headless (EGL); on llvmpipe the
// times are a CPU rasteriser's, so the figure to read is the textured / untextured ratio of the same
// run: of the best frames (the least disturbed by other load) and of the medians. Texture sizes 1x1 and
// 64x64 (always in cache) give the fixed cost of one filtered lookup per pixel on this device; 256^2 and
// 1024^2 add what cache misses cost.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <map>
#include <string>
#include <vector>

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
  // 8-bit sRGB codes, as a PNG or JPEG base colour decodes (mesh::Texture::codes).
  texture.codes.resize(3 * static_cast<std::size_t>(size) * size);
  for (std::size_t i = 0; i < texture.codes.size(); ++i) texture.codes[i] = static_cast<std::uint8_t>((i * 7919) % 251);
  m.textures.push_back(texture);
  m.albedo_source = mesh::AlbedoSource::texture;
  return m;
}

// Per texture size: each kind's frame times, textured and untextured alternated frame by frame.
// Wall time, and the process's CPU time (llvmpipe's rasteriser threads included): on a machine shared
// with other work the CPU time leaves out the waits for a core.
struct Times {
  std::vector<double> textured_ms, untextured_ms, textured_cpu_ms, untextured_cpu_ms;
};
std::map<int, Times> results;

double cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

// One frame: appends its wall and CPU milliseconds.
void frame_ms(render::Renderer& renderer, const render::FrameSettings& settings, std::vector<double>& wall,
              std::vector<double>& cpu) {
  const double cpu_start = cpu_ms();
  const auto start = std::chrono::steady_clock::now();
  renderer.render(settings, kFrameSize, kFrameSize);
  glFinish();
  wall.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  cpu.push_back(cpu_ms() - cpu_start);
}

double best(std::vector<double> v) { return *std::min_element(v.begin(), v.end()); }
double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

void frame_textured_vs_untextured(benchmark::State& state, render::Renderer& renderer, int size) {
  const mesh::Mesh mesh = textured_floor(64, size);
  renderer.set_mesh(mesh);
  const transfer::TransferData data = bench::synthetic_diffuse(mesh);
  const int textured = renderer.add_transfer(data, "synthetic");
  renderer.set_textured(textured, true);
  const int plain = renderer.add_transfer(data, "synthetic");
  renderer.set_lighting(bench::synthetic_lighting(5), nullptr);
  const render::Camera camera{30.0, 40.0, 0.0};
  const render::FrameSettings a = bench::black_frame(textured, camera), b = bench::black_frame(plain, camera);
  Times warm_up;  // shader compilation, first-use allocation
  frame_ms(renderer, a, warm_up.textured_ms, warm_up.textured_cpu_ms);
  frame_ms(renderer, b, warm_up.untextured_ms, warm_up.untextured_cpu_ms);
  Times& times = results[size];
  for (auto _ : state) {
    frame_ms(renderer, a, times.textured_ms, times.textured_cpu_ms);
    frame_ms(renderer, b, times.untextured_ms, times.untextured_cpu_ms);
    state.SetIterationTime(1e-3 * times.textured_ms.back());
  }
  state.counters["textured_best_ms"] = best(times.textured_ms);
  state.counters["untextured_best_ms"] = best(times.untextured_ms);
  state.counters["best_ratio"] = best(times.textured_ms) / best(times.untextured_ms);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  render::HeadlessContext context;
  std::printf("bench_render_texture: %s; frames %dx%d, 5 bands RGB\n", context.description().c_str(), kFrameSize, kFrameSize);
  render::Renderer renderer;
  for (int size : {1, 64, 256, 1024}) {
    const std::string name = "frame_textured_vs_untextured/texture:" + std::to_string(size);
    benchmark::RegisterBenchmark(name.c_str(), [&renderer, size](benchmark::State& state) {
      frame_textured_vs_untextured(state, renderer, size);
    })->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(2.0);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  std::printf("\nSummary (floor of 8192 triangles filling most of the frame, the texture repeated twice across it;\n"
              "best and median of each kind's frames, alternated frame by frame)\n");
  for (const auto& [size, t] : results)
    std::printf("texture %4dx%-4d  textured best %7.2f ms (median %7.2f)  untextured best %7.2f ms (median %7.2f)  "
                "ratio of bests %.3f, of medians %.3f  (%zu frames each)\n",
                size, size, best(t.textured_ms), median(t.textured_ms), best(t.untextured_ms), median(t.untextured_ms),
                best(t.textured_ms) / best(t.untextured_ms), median(t.textured_ms) / median(t.untextured_ms),
                t.textured_ms.size());
  for (const auto& [size, t] : results)
    std::printf("texture %4dx%-4d  CPU time: textured best %7.2f ms (median %7.2f)  untextured best %7.2f ms (median %7.2f)  "
                "ratio of bests %.3f, of medians %.3f\n",
                size, size, best(t.textured_cpu_ms), median(t.textured_cpu_ms), best(t.untextured_cpu_ms),
                median(t.untextured_cpu_ms), best(t.textured_cpu_ms) / best(t.untextured_cpu_ms),
                median(t.textured_cpu_ms) / median(t.untextured_cpu_ms));
  return 0;
}
