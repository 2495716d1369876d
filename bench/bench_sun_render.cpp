// Sun benchmarks (issue "Sun and sky"): the frame with one disc's shadow map (PCSS lookups per pixel,
// maps not redrawn) against the PRT-only frame on the same mesh, camera and transfer, 1024x1024,
// alternating frame by frame; and the frame right after a lighting rotation (shadow map redrawn and
// the disc's bounce light recomputed inside it), each followed by the same frame again (nothing
// redrawn, the same picture): their difference is the redraw's cost. Headless (EGL); on llvmpipe
// read the ratios.
#include <benchmark/benchmark.h>

#include <chrono>
#include <ctime>
#include <cstdio>
#include <string>

#include "light/disc.h"
#include "mesh/mesh.h"
#include "bench_lighting.h"
#include "render/gl.h"
#include "render/headless_context.h"
#include "render/renderer.h"
#include "sh/rotation.h"

using namespace prt;
using bench::synthetic_lighting;

namespace {

constexpr double kTargetSunRatio = 1.3;
constexpr int kFrameSize = 1024;

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }
// CPU time of the whole process (all of llvmpipe's threads): robust to other jobs on a shared machine.
double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

// A shadowed-kind transfer with a bounce-only part: the values do not change the cost.
transfer::TransferData synthetic_transfer(std::size_t vertices, int bands) {
  transfer::TransferData data;
  data.header.kind = transfer::Kind::interreflected;
  data.header.bands = static_cast<std::uint32_t>(bands);
  data.header.channels = 3;
  data.header.vertex_count = vertices;
  data.header.bounce_only_section = true;
  data.values.resize(vertices * data.header.values_per_vertex());
  for (std::size_t i = 0; i < data.values.size(); ++i) data.values[i] = 0.01f * static_cast<float>((i * 7919) % 97);
  data.bounce_only = data.values;
  for (float& v : data.bounce_only) v *= 0.1f;
  return data;
}

// What one or more finished frames took: wall and process CPU seconds, shadow maps redrawn.
struct TimedFrame {
  double seconds = 0.0, cpu_seconds = 0.0;
  int map_updates = 0;
  TimedFrame& operator+=(const TimedFrame& o) {
    seconds += o.seconds;
    cpu_seconds += o.cpu_seconds;
    map_updates += o.map_updates;
    return *this;
  }
  double ms(int frames) const { return 1e3 * seconds / frames; }
  double cpu_ms(int frames) const { return 1e3 * cpu_seconds / frames; }
};

// One frame, rendered and finished.
TimedFrame timed_frame(render::Renderer& renderer, const render::FrameSettings& settings) {
  const int before = renderer.shadow_map_updates();
  const auto start = Clock::now();
  const double cpu = cpu_seconds();
  renderer.render(settings, kFrameSize, kFrameSize);
  glFinish();
  TimedFrame t;
  t.seconds = seconds_since(start);
  t.cpu_seconds = cpu_seconds() - cpu;
  t.map_updates = renderer.shadow_map_updates() - before;
  return t;
}

// Totals over the timed frames of both benchmarks: PRT-only and with the disc, frame by frame; a frame
// after a lighting rotation and the same frame again.
struct Figures {
  TimedFrame prt, sun, rotated, same;
  int frames = 0, rotated_frames = 0;
};

// Times `first` then `second` state.iterations() times, adding them to *a and *b; the manual time is
// `first`'s wall time when time_first, else `second`'s. Returns the iteration count. `before_each` runs
// before each pair.
template <typename BeforeEach>
int time_pairs(benchmark::State& state, render::Renderer& renderer, const render::FrameSettings& first,
               const render::FrameSettings& second, bool time_first, TimedFrame* a, TimedFrame* b,
               BeforeEach before_each) {
  *a = {};
  *b = {};
  for (auto _ : state) {
    before_each();
    const TimedFrame x = timed_frame(renderer, first);
    const TimedFrame y = timed_frame(renderer, second);
    *a += x;
    *b += y;
    state.SetIterationTime(time_first ? x.seconds : y.seconds);
  }
  return static_cast<int>(state.iterations());
}

void print_summary(const Figures& f, std::size_t vertices) {
  const int n = f.frames, r = f.rotated_frames;
  std::printf("\nSummary (machine shared and noisy: compare within this run)\n");
  std::printf("lion (%zu vertices), 1024x1024, 5 bands RGB, one disc, shadow map %dx%d:\n", vertices,
              render::kShadowMapSize, render::kShadowMapSize);
  std::printf("  PRT-only frame %.2f ms, frame with the disc %.2f ms: x%.3f (target <= %.1f)\n", f.prt.ms(n), f.sun.ms(n),
              f.sun.ms(n) / f.prt.ms(n), kTargetSunRatio);
  std::printf("  the same in process CPU time (all threads): %.2f ms and %.2f ms: x%.3f\n", f.prt.cpu_ms(n),
              f.sun.cpu_ms(n), f.sun.cpu_ms(n) / f.prt.cpu_ms(n));
  std::printf("  frame right after a lighting rotation (map redrawn + bounce recomputed in it): %.2f ms, %d redraws in %d "
              "frames; the same frame again: %.2f ms, %d redraws; the redraw itself %.2f ms\n",
              f.rotated.ms(r), f.rotated.map_updates, r, f.same.ms(r), f.same.map_updates, f.rotated.ms(r) - f.same.ms(r));
  std::printf("  in CPU time: %.2f ms and %.2f ms, the redraw itself %.2f ms\n", f.rotated.cpu_ms(r), f.same.cpu_ms(r),
              f.rotated.cpu_ms(r) - f.same.cpu_ms(r));
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  render::HeadlessContext context;
  std::printf("bench_sun_render: %s; frames %dx%d\n", context.description().c_str(), kFrameSize, kFrameSize);
  render::Renderer renderer;
  const mesh::Mesh mesh = mesh::load_mesh(PRT_SOURCE_DIR "/assets/meshes/guardian_lion_10k.ply", nullptr, true);
  renderer.set_mesh(mesh);
  const int index = renderer.add_transfer(synthetic_transfer(mesh.vertex_count(), 5), "synthetic");
  renderer.set_lighting(synthetic_lighting(5), nullptr);
  light::Disc sun;
  sun.direction = glm::normalize(glm::dvec3(0.8, 0.4, 0.45));
  sun.irradiance = glm::dvec3(5.0, 4.8, 3.5);
  sun.angular_radius = 0.53 * 3.14159265358979323846 / 180.0;
  renderer.set_discs({sun});
  Figures f;

  render::FrameSettings prt;
  prt.transfer = index;
  prt.background = render::Background::sh;  // a full-screen pass per pixel, as in the viewer
  prt.camera = render::Camera{30.0, 20.0, 0.0};
  prt.sun = false;
  render::FrameSettings with_sun = prt;
  with_sun.sun = true;

  benchmark::RegisterBenchmark("frame_sun_vs_prt/lion/1024x1024", [&](benchmark::State& state) {
    for (const auto* settings : {&prt, &with_sun}) {  // warm-up: shader compilation, the first map
      renderer.render(*settings, kFrameSize, kFrameSize);
      glFinish();
    }
    f.frames = time_pairs(state, renderer, prt, with_sun, false, &f.prt, &f.sun, [] {});
    state.counters["prt_ms"] = f.prt.ms(f.frames);
    state.counters["sun_ms"] = f.sun.ms(f.frames);
    state.counters["sun/prt"] = f.sun.ms(f.frames) / f.prt.ms(f.frames);
    state.counters["target_ratio"] = kTargetSunRatio;
  })->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(3.0);

  double angle = 0.0;  // kept across the library's repeated runs, so every timed frame has a new rotation
  benchmark::RegisterBenchmark("frame_after_lighting_rotation/lion/1024x1024", [&](benchmark::State& state) {
    render::FrameSettings turning = with_sun;
    // The map is redrawn inside the first frame of each pair; the second is the same picture, nothing redrawn.
    f.rotated_frames = time_pairs(state, renderer, turning, turning, true, &f.rotated, &f.same, [&] {
      angle += 3.0;
      turning.environment_rotation = sh::rotation_from_yaw_pitch_roll(angle, 0.0, 0.0);
    });
    state.counters["ms"] = f.rotated.ms(f.rotated_frames);
    state.counters["map_redraws_per_frame"] = static_cast<double>(f.rotated.map_updates) / f.rotated_frames;
  })->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(3.0);

  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();

  print_summary(f, mesh.vertex_count());
  return 0;
}
