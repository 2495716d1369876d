#pragma once
// Shared by the renderer benchmarks that compare two kinds of frame on one mesh: a floor grid, and the
// timing of two frame settings alternated frame by frame (so that both see the same machine load).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <vector>

#include "mesh/mesh.h"
#include "render/gl.h"
#include "render/renderer.h"
#include "sh/rotation.h"
#include "transfer/transfer_file.h"

namespace prt::bench {

/// A floor of n x n quads over [-1, 1]^2 (y = 0), normals +Y, two triangles per quad; `uv`, if not
/// null, gets one UV per triangle corner: ((x + 1) / 2, (z + 1) / 2) times `uv_scale`.
inline mesh::Mesh floor_grid(int n, std::vector<glm::vec2>* uv = nullptr, float uv_scale = 1.0f) {
  mesh::Mesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      m.positions.emplace_back(-1.0f + 2.0f * i / n, 0.0f, -1.0f + 2.0f * j / n);
      m.normals.emplace_back(0.0f, 1.0f, 0.0f);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const auto at = [n](int a, int b) { return static_cast<std::uint32_t>(b * (n + 1) + a); };
      for (std::uint32_t v : {at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i + 1, j)}) {
        m.indices.push_back(v);
        if (uv) uv->push_back(uv_scale * glm::vec2((m.positions[v].x + 1.0f) / 2.0f, (m.positions[v].z + 1.0f) / 2.0f));
      }
    }
  return m;
}

/// A shadowed 5-band RGB transfer for `mesh`, per vertex (texels 0) or per texel of a texels^2
/// lightmap; the values, a fixed pattern, do not change the cost.
inline transfer::TransferData synthetic_diffuse(const mesh::Mesh& mesh, int texels = 0) {
  transfer::TransferData d;
  d.header.kind = transfer::Kind::shadowed;
  d.header.bands = 5;
  d.header.channels = 3;
  d.header.vertex_count = mesh.vertex_count();
  d.header.triangle_count = mesh.triangle_count();
  d.header.texel_width = d.header.texel_height = static_cast<std::uint32_t>(texels);
  d.values.resize(d.header.block_count() * d.header.values_per_vertex());
  for (std::size_t i = 0; i < d.values.size(); ++i) d.values[i] = 0.01f * static_cast<float>((i * 7919) % 97);
  return d;
}

/// Frame settings of transfer `transfer` on a black background from `camera` (other fields default).
inline render::FrameSettings black_frame(int transfer, const render::Camera& camera) {
  render::FrameSettings settings;
  settings.transfer = transfer;
  settings.background = render::Background::black;
  settings.camera = camera;
  return settings;
}

/// Median milliseconds of 7 frames of `settings` at size x size, after 2 warm-up frames (shader
/// compilation, first-use allocation), each frame ended by glFinish.
inline double median_frame_ms(render::Renderer& renderer, const render::FrameSettings& settings, int size = 1024) {
  std::vector<double> ms;
  for (int frame = 0; frame < 9; ++frame) {
    const auto start = std::chrono::steady_clock::now();
    renderer.render(settings, size, size);
    glFinish();
    if (frame >= 2) ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(ms.begin(), ms.end());
  return ms[ms.size() / 2];
}

/// Mean milliseconds per frame of settings a and b, rendered alternately at size x size (after one
/// warm-up frame of each: shader compilation, first-use allocation); the benchmark's time is a's.
/// With `turn_sky`, the environment turns by a new yaw (7 degrees more) every frame, the same for a and
/// b: frames with a lighting change.
struct FramePair {
  double a_ms = 0.0, b_ms = 0.0;
};
inline FramePair alternate_frames(benchmark::State& state, render::Renderer& renderer, render::FrameSettings a,
                                  render::FrameSettings b, int size, bool turn_sky = false) {
  using Clock = std::chrono::steady_clock;
  const auto seconds_since = [](Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); };
  for (const auto* s : {&a, &b}) {
    renderer.render(*s, size, size);
    glFinish();
  }
  double sum_a = 0.0, sum_b = 0.0;
  int frame = 0;
  for (auto _ : state) {
    if (turn_sky) a.environment_rotation = b.environment_rotation = sh::rotation_from_yaw_pitch_roll(7.0 * ++frame, 0.0, 0.0);
    auto start = Clock::now();
    renderer.render(a, size, size);
    glFinish();
    const double t = seconds_since(start);
    start = Clock::now();
    renderer.render(b, size, size);
    glFinish();
    sum_b += seconds_since(start);
    sum_a += t;
    state.SetIterationTime(t);
  }
  const double n = static_cast<double>(state.iterations());
  return {1e3 * sum_a / n, 1e3 * sum_b / n};
}

}  // namespace prt::bench
