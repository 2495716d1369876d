// Renderer benchmarks (issue "Real-time relighting"): per-frame CPU cost of the lighting rotation and
// upload, PRT frame time against a plain Lambert shader on the same mesh and camera, and the one-time
// transfer upload. Headless (EGL); on llvmpipe the absolute frame times are a CPU rasteriser's, so the
// figure to read is the PRT / Lambert ratio measured in the same run.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bench_meshes.h"
#include "bench_frames.h"
#include "bench_lighting.h"
#include "render/gl.h"
#include "render/headless_context.h"
#include "render/renderer.h"
#include "sh/rotation.h"

using namespace prt;
using bench::synthetic_lighting;

namespace {

constexpr double kTargetLightingUpdateUs = 20.0;
constexpr double kTargetFrameRatio = 1.5;
constexpr double kTargetUploadMs = 100.0;
constexpr int kFrameSize = 1024;

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Transfer values do not change the cost; any fixed pattern will do.
transfer::TransferData synthetic_transfer(std::size_t vertices, int bands, int channels) {
  transfer::TransferData data;
  data.header.kind = transfer::Kind::interreflected;
  data.header.bands = static_cast<std::uint32_t>(bands);
  data.header.channels = static_cast<std::uint32_t>(channels);
  data.header.vertex_count = vertices;
  data.values.resize(vertices * data.header.values_per_vertex());
  for (std::size_t i = 0; i < data.values.size(); ++i) data.values[i] = 0.01f * static_cast<float>((i * 7919) % 97);
  return data;
}

struct FrameResult {
  double prt_ms = 0.0, lambert_ms = 0.0;
};

// What the benchmarks leave for the summary.
struct Results {
  std::map<int, FrameResult> frames;  // by icosphere level
  double lighting_update_us = 0.0, upload_ms = 0.0, host_copy_ms = 0.0;
};

void register_lighting(render::Renderer& renderer, Results& results) {
  // 1. Per-frame CPU work: rotate the lighting by R_object^-1 R_environment and upload it.
  for (int bands : {3, 5, 8, 16}) {
    const std::string name = "lighting_rotate_upload/bands:" + std::to_string(bands) + "/rgb";
    benchmark::RegisterBenchmark(name.c_str(), [&renderer, bands, &results](benchmark::State& state) {
      renderer.set_mesh(bench::icosphere(1));
      renderer.set_lighting(synthetic_lighting(bands), nullptr);
      double angle = 0.0;
      const auto start = Clock::now();
      for (auto _ : state) {
        angle += 0.7;
        renderer.update_lighting(sh::rotation_from_yaw_pitch_roll(angle, 0.3 * angle, 0.0),
                                 sh::rotation_from_yaw_pitch_roll(0.0, 10.0, 0.0), bands);
      }
      const double us = 1e6 * seconds_since(start) / static_cast<double>(state.iterations());
      glFinish();
      state.counters["us/frame"] = us;
      if (bands == 5) results.lighting_update_us = us;
      if (bands == 5) state.counters["target_us"] = kTargetLightingUpdateUs;
    })->Unit(benchmark::kMicrosecond);
  }
  // The same, only the rotation (no GL call), for the breakdown.
  benchmark::RegisterBenchmark("lighting_rotate_only/bands:5/rgb", [](benchmark::State& state) {
    std::vector<glm::vec3> in(25, glm::vec3(0.5f)), out(25);
    float angle = 0.0f;
    for (auto _ : state) {
      angle += 0.7f;
      sh::rotate_rgb(5, glm::mat3(sh::rotation_from_yaw_pitch_roll(angle, 0.3 * angle, 0.0)), in.data(), out.data());
      benchmark::DoNotOptimize(out.data());
    }
  })->Unit(benchmark::kMicrosecond);

}

void register_frames(render::Renderer& renderer, Results& results) {
  // 2. Frame time, PRT (5 bands RGB) against Lambert, same mesh and camera, alternating frame by frame.
  for (int levels : {6, 7, 8}) {
    const std::string name = "frame_prt_vs_lambert/icosphere:" + std::to_string(levels) + "/" +
                             std::to_string(kFrameSize) + "x" + std::to_string(kFrameSize);
    benchmark::RegisterBenchmark(name.c_str(), [&renderer, levels, &results](benchmark::State& state) {
      const mesh::Mesh mesh = bench::bumpy_icosphere(levels, 0.3f);
      renderer.set_mesh(mesh);
      const int index = renderer.add_transfer(synthetic_transfer(mesh.vertex_count(), 5, 3), "synthetic");
      renderer.set_lighting(synthetic_lighting(5), nullptr);
      render::FrameSettings prt;
      prt.transfer = index;
      prt.background = render::Background::black;
      prt.camera = render::Camera{30.0, 20.0, 0.0};
      render::FrameSettings lambert = prt;
      lambert.shading = render::Shading::lambert;
      const bench::FramePair times = bench::alternate_frames(state, renderer, prt, lambert, kFrameSize);
      FrameResult& r = results.frames[levels];
      r.prt_ms = times.a_ms;
      r.lambert_ms = times.b_ms;
      state.counters["vertices"] = static_cast<double>(mesh.vertex_count());
      state.counters["triangles"] = static_cast<double>(mesh.triangle_count());
      state.counters["prt_ms"] = r.prt_ms;
      state.counters["lambert_ms"] = r.lambert_ms;
      state.counters["prt/lambert"] = r.prt_ms / r.lambert_ms;
      state.counters["target_ratio"] = kTargetFrameRatio;
    })->UseManualTime()->Unit(benchmark::kMillisecond)->MinTime(2.0);
  }
}

void register_uploads(Results& results) {
  // 3. One-time upload of a 400k-vertex, 5-band RGB transfer (120 MB of floats) into its storage buffer.
  benchmark::RegisterBenchmark("transfer_upload/vertices:400000/bands:5/rgb", [&results](benchmark::State& state) {
    const transfer::TransferData data = synthetic_transfer(400000, 5, 3);
    double total = 0.0;
    for (auto _ : state) {
      const auto start = Clock::now();
      render::TransferBuffer buffer(data, "synthetic");
      glFinish();
      const double s = seconds_since(start);
      total += s;
      state.SetIterationTime(s);
    }
    results.upload_ms = 1e3 * total / static_cast<double>(state.iterations());
    state.counters["MB"] = static_cast<double>(data.values.size() * sizeof(float)) * 1e-6;
    state.counters["ms"] = results.upload_ms;
    state.counters["target_ms"] = kTargetUploadMs;
  })->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(5);

  // Baseline for 3: copying the same values into fresh host memory (a std::vector), which pays the same
  // first-touch page faults as the driver's allocation.
  benchmark::RegisterBenchmark("transfer_upload_baseline/host_copy/vertices:400000/bands:5/rgb",
                               [&results](benchmark::State& state) {
    const transfer::TransferData data = synthetic_transfer(400000, 5, 3);
    double total = 0.0;
    for (auto _ : state) {
      const auto start = Clock::now();
      std::vector<float> copy(data.values);
      benchmark::DoNotOptimize(copy.data());
      const double s = seconds_since(start);
      total += s;
      state.SetIterationTime(s);
    }
    results.host_copy_ms = 1e3 * total / static_cast<double>(state.iterations());
    state.counters["ms"] = results.host_copy_ms;
  })->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(5);
}

void print_summary(const Results& results) {
  std::printf("\nSummary (machine shared and noisy: compare ratios within this run)\n");
  std::printf("%-34s %10s %10s %10s %12s %8s\n", "mesh (1024x1024, 5 bands RGB)", "triangles", "PRT ms", "Lambert ms",
              "PRT/Lambert", "target");
  for (const auto& [levels, r] : results.frames)
    std::printf("bumpy icosphere level %-12d %10d %10.2f %10.2f %12.3f %8.1f\n", levels, 20 * (1 << (2 * levels)),
                r.prt_ms, r.lambert_ms, r.prt_ms / r.lambert_ms, kTargetFrameRatio);
  if (results.upload_ms > 0.0)
    std::printf("transfer upload, 400k vertices, 5 bands RGB (120 MB): %.1f ms (target <= %.0f ms); a plain host copy "
                "of the same values into fresh memory: %.1f ms (x%.2f)\n",
                results.upload_ms, kTargetUploadMs, results.host_copy_ms,
                results.host_copy_ms > 0.0 ? results.upload_ms / results.host_copy_ms : 0.0);
  std::printf("lighting rotation + upload per frame, 5 bands RGB: %.2f us (target <= %.0f us)\n",
              results.lighting_update_us, kTargetLightingUpdateUs);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  render::HeadlessContext context;
  std::printf("bench_render: %s; frames %dx%d\n", context.description().c_str(), kFrameSize, kFrameSize);
  render::Renderer renderer;
  Results results;
  register_lighting(renderer, results);
  register_frames(renderer, results);
  register_uploads(results);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  print_summary(results);
  return 0;
}
