// Mixed scenes (issue 35, item 5): a lightmapped floor with a per-vertex sphere on it, drawn in one frame
// (Renderer::add_mixed: each pass draws its own triangles into one frame and depth buffer) against the
// path it replaces (commit a67c574, render/mixed_frame.cpp before this: the whole frame drawn once with
// each transfer, both read back, and each pixel kept from its triangle's kind on the CPU), and against one
// plain frame of the lightmap alone. Alternated frame by frame so all three see the same load; both
// "to an image" (what `prt render` does: the frame read back as radiance) and the draw alone (what the
// viewer does each frame). Headless (EGL); on llvmpipe the absolute times are a CPU rasteriser's, so the
// figures to read are the ratios measured in the same run.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <utility>
#include <cstdio>
#include <vector>

#include "bench_frames.h"
#include "bench_lighting.h"
#include "bench_meshes.h"
#include "light/disc.h"
#include "render/headless_context.h"
#include "render/renderer.h"

using namespace prt;

namespace {

constexpr int kFrameSize = 1024, kTexels = 512, kRounds = 9;
using Clock = std::chrono::steady_clock;

// The floor grid (8192 triangles, lightmap UVs) then an icosphere of 20,480 triangles standing on it,
// drawn per vertex (its corners' lightmap UVs are 0, never read).
mesh::Mesh floor_and_sphere(render::TriangleRuns& sphere_runs) {
  std::vector<glm::vec2> uv;
  mesh::Mesh m = bench::floor_grid(64, &uv);
  const mesh::Mesh sphere = bench::icosphere(5, 0.4f, glm::vec3(0.0f, 0.4f, 0.0f));
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  sphere_runs = {{m.triangle_count(), sphere.triangle_count()}};
  m.positions.insert(m.positions.end(), sphere.positions.begin(), sphere.positions.end());
  m.normals.insert(m.normals.end(), sphere.normals.begin(), sphere.normals.end());
  for (std::uint32_t v : sphere.indices) m.indices.push_back(base + v);
  uv.resize(m.indices.size(), glm::vec2(0.0f));
  m.lightmap_uv = uv;
  return m;
}

// Today's path before this change: two whole frames, both read back, composited per triangle id.
image::Image two_frame_composite(render::Renderer& renderer, render::FrameSettings settings, int texel, int vertex,
                                 const std::vector<std::uint8_t>& per_vertex) {
  settings.transfer = texel;
  renderer.render(settings, kFrameSize, kFrameSize);
  image::Image frame = renderer.read_radiance();
  const std::vector<std::uint32_t> ids = renderer.read_triangle_ids();
  settings.transfer = vertex;
  renderer.render(settings, kFrameSize, kFrameSize);
  const image::Image vertex_frame = renderer.read_radiance();
  for (std::size_t p = 0; p < ids.size(); ++p)
    if (ids[p] != render::kNoTriangle && per_vertex[ids[p]])
      for (int c = 0; c < 3; ++c) frame.pixels[p * 3 + c] = vertex_frame.pixels[p * 3 + c];
  return frame;
}

// Wall and process CPU time (every thread: llvmpipe rasterises on its own threads), in ms.
struct Stopwatch {
  Clock::time_point wall = Clock::now();
  std::clock_t cpu = std::clock();
  std::pair<double, double> ms() const {
    return {std::chrono::duration<double, std::milli>(Clock::now() - wall).count(),
            1e3 * static_cast<double>(std::clock() - cpu) / CLOCKS_PER_SEC};
  }
};

struct Times {
  std::vector<double> one, two, texel_only, one_cpu, two_cpu, texel_cpu, one_draw, two_draws;
  void add(const std::pair<double, double>& a, const std::pair<double, double>& b, const std::pair<double, double>& c) {
    one.push_back(a.first), one_cpu.push_back(a.second);
    two.push_back(b.first), two_cpu.push_back(b.second);
    texel_only.push_back(c.first), texel_cpu.push_back(c.second);
  }
};

double best(std::vector<double> v) { return *std::min_element(v.begin(), v.end()); }
double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main() {
  render::HeadlessContext context;
  std::printf("bench_render_mixed: %s; frames %dx%d, 5 bands RGB, lightmap %dx%d\n", context.description().c_str(), kFrameSize,
              kFrameSize, kTexels, kTexels);
  render::Renderer renderer;
  render::TriangleRuns sphere_runs;
  const mesh::Mesh mesh = floor_and_sphere(sphere_runs);
  renderer.set_mesh(mesh);
  const int texel = renderer.add_lightmap(bench::synthetic_diffuse(mesh, kTexels), "synthetic texels");
  const int vertex = renderer.add_transfer(bench::synthetic_diffuse(mesh), "synthetic vertices");
  const int mixed = renderer.add_mixed(texel, vertex, sphere_runs);
  std::vector<std::uint8_t> per_vertex(mesh.triangle_count(), 0);
  for (const auto& [first, count] : sphere_runs) std::fill_n(per_vertex.begin() + first, count, 1);
  renderer.set_lighting(bench::synthetic_lighting(5), nullptr);
  renderer.set_discs({light::parse_disc("0.48,0.8,0.36,3,3,3,3")});  // direction, E, radius in degrees

  for (bool with_sun : {false, true}) {
    render::FrameSettings settings = bench::black_frame(mixed, render::Camera{30.0, 35.0, 0.0});
    settings.sun = with_sun;
    render::FrameSettings texel_settings = settings;
    texel_settings.transfer = texel;
    Times t;
    for (int round = -1; round < kRounds; ++round) {  // round -1: warm-up (shaders, allocations)
      Stopwatch watch;
      renderer.render(settings, kFrameSize, kFrameSize);
      const image::Image one = renderer.read_radiance();
      const auto one_ms = watch.ms();
      watch = Stopwatch();
      const image::Image two = two_frame_composite(renderer, settings, texel, vertex, per_vertex);
      const auto two_ms = watch.ms();
      watch = Stopwatch();
      renderer.render(texel_settings, kFrameSize, kFrameSize);
      const image::Image plain = renderer.read_radiance();
      const auto texel_ms = watch.ms();
      const double one_draw = bench::median_frame_ms(renderer, settings, kFrameSize);
      render::FrameSettings a = settings, b = settings;
      a.transfer = texel;
      b.transfer = vertex;
      const double two_draws = bench::median_frame_ms(renderer, a, kFrameSize) + bench::median_frame_ms(renderer, b, kFrameSize);
      if (round < 0) continue;
      if (round == 0) {
        double diff = 0.0;
        for (std::size_t i = 0; i < one.pixels.size(); ++i) diff = std::max(diff, double(std::abs(one.pixels[i] - two.pixels[i])));
        std::printf("%s: one frame against the two-frame composite: max |difference| %.3g\n", with_sun ? "sun" : "sky", diff);
      }
      t.add(one_ms, two_ms, texel_ms);
      t.one_draw.push_back(one_draw);
      t.two_draws.push_back(two_draws);
    }
    std::printf("\n%s: %d rounds, ms best / median\n", with_sun ? "with a sun (shadow map, deferred direct light)" : "sky only", kRounds);
    std::printf("  to an image: one frame %.1f / %.1f, two frames + composite %.1f / %.1f, lightmap alone %.1f / %.1f\n",
                best(t.one), median(t.one), best(t.two), median(t.two), best(t.texel_only), median(t.texel_only));
    std::printf("  ratio one / two-frame path: %.2f best, %.2f median; one / lightmap alone: %.2f best, %.2f median\n",
                best(t.one) / best(t.two), median(t.one) / median(t.two), best(t.one) / best(t.texel_only),
                median(t.one) / median(t.texel_only));
    std::printf("  process CPU: one frame %.1f / %.1f, two frames + composite %.1f / %.1f, lightmap alone %.1f / %.1f; "
                "ratio one / two %.2f best, %.2f median\n",
                best(t.one_cpu), median(t.one_cpu), best(t.two_cpu), median(t.two_cpu), best(t.texel_cpu), median(t.texel_cpu),
                best(t.one_cpu) / best(t.two_cpu), median(t.one_cpu) / median(t.two_cpu));
    std::printf("  draw only (median of 7 frames each round): one frame %.1f / %.1f, two frames %.1f / %.1f, ratio %.2f best\n",
                best(t.one_draw), median(t.one_draw), best(t.two_draws), median(t.two_draws), best(t.one_draw) / best(t.two_draws));
  }
  return 0;
}
