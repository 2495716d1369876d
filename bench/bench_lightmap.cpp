// bench_lightmap: texel (lightmap) bake throughput per sample point against the per-vertex bake of
// the same mesh at equal samples, in one run (issue 12).
//
// Mesh: a heightfield terrain of C x C cells (2 C^2 triangles; C = 224: 100,352 triangles, 50,625
// vertices) with ridged bumps that shadow each other, lightmap UVs = its planar (x, z) projection
// (one chart). The lightmap has about as many texels as the mesh has vertices (C x C).
// Targets: texel shadowed bake <= 1.25 x the per-vertex shadowed bake per sample point (the texel
// figure includes rasterization and sample repair); texel bounce pass <= 1.5 x the per-vertex bounce
// pass per point.
// Usage: bench_lightmap [--samples S] [--cells C] [--threads T] [--write-terrain PATH.obj]
// With --write-terrain it only writes the terrain (OBJ with vt) for timing `prt bake --lightmap
// 1024` under /usr/bin/time -v.
// A timed program, not Google Benchmark: each bake runs once, back to back, on a shared machine.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#include "bake/bake.h"
#include "lightmap/texel_bake.h"

using namespace prt;

namespace {

struct Args {
  int samples = 256, cells = 224, threads = 2;
  std::string write_terrain;
};

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const bool has_value = i + 1 < argc;
    if (!std::strcmp(argv[i], "--samples") && has_value) a.samples = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--cells") && has_value) a.cells = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--threads") && has_value) a.threads = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--write-terrain") && has_value) a.write_terrain = argv[++i];
    else {
      std::fprintf(stderr, "usage: bench_lightmap [--samples S] [--cells C] [--threads T] [--write-terrain PATH.obj]\n");
      std::exit(2);
    }
  }
  return a;
}

float height(float x, float z) {
  return 0.12f * (std::abs(std::sin(3.1f * x + 0.4f)) + std::abs(std::sin(4.7f * z + 1.3f * x)) +
                  0.5f * std::abs(std::sin(11.0f * (x + z))) - 1.2f);
}

// Welded grid over [-1, 1]^2, vertex (i, k) at uv (i / C, k / C) (v down = +z).
mesh::Mesh terrain(int cells) {
  mesh::Mesh m;
  const int n = cells + 1;
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < n; ++i) {
      const float x = -1.0f + 2.0f * float(i) / float(cells), z = -1.0f + 2.0f * float(k) / float(cells);
      m.positions.emplace_back(x, height(x, z), z);
    }
  for (int k = 0; k < cells; ++k)
    for (int i = 0; i < cells; ++i) {
      const std::uint32_t a = std::uint32_t(i + k * n), b = a + 1, c = a + std::uint32_t(n), d = c + 1;
      for (std::uint32_t v : {a, c, b, b, c, d}) {  // counter-clockwise seen from +y
        m.indices.push_back(v);
        m.lightmap_uv.emplace_back(float(v % std::uint32_t(n)) / float(cells), float(v / std::uint32_t(n)) / float(cells));
      }
    }
  m.normals = mesh::area_weighted_normals(m.positions, m.indices);
  return m;
}

void write_obj(const std::string& path, const mesh::Mesh& m, int cells) {
  std::ofstream out(path);
  out.precision(9);
  for (const glm::vec3& p : m.positions) out << "v " << p.x << " " << p.y << " " << p.z << "\n";
  const int n = cells + 1;
  for (std::size_t v = 0; v < m.positions.size(); ++v)  // OBJ's v points up: 1 - v
    out << "vt " << float(v % std::size_t(n)) / float(cells) << " " << 1.0f - float(v / std::size_t(n)) / float(cells) << "\n";
  for (std::size_t c = 0; c < m.indices.size(); c += 3)
    out << "f " << m.indices[c] + 1 << "/" << m.indices[c] + 1 << " " << m.indices[c + 1] + 1 << "/" << m.indices[c + 1] + 1 << " "
        << m.indices[c + 2] + 1 << "/" << m.indices[c + 2] + 1 << "\n";
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  const Args a = parse(argc, argv);
  const mesh::Mesh m = terrain(a.cells);
  if (!a.write_terrain.empty()) {
    write_obj(a.write_terrain, m, a.cells);
    std::printf("wrote %s: %zu vertices, %zu triangles\n", a.write_terrain.c_str(), m.vertex_count(), m.triangle_count());
    return 0;
  }
  bake::BakeOptions options;
  options.samples = a.samples;
  options.threads = a.threads;
  options.kind = transfer::Kind::interreflected;
  options.bounces = 1;
  lightmap::LightmapOptions l;
  l.width = l.height = a.cells;
  std::printf("bench_lightmap: terrain %zu vertices, %zu triangles, lightmap %dx%d, %d samples, %d threads\n", m.vertex_count(),
              m.triangle_count(), l.width, l.height, a.samples, a.threads);

  auto start = std::chrono::steady_clock::now();
  bake::BakeReport vertex;
  bake::bake(m, options, &vertex);
  const double vertex_total = seconds_since(start);
  start = std::chrono::steady_clock::now();
  lightmap::LightmapReport texel;
  lightmap::bake_lightmap(m, options, l, &texel);
  const double texel_total = seconds_since(start);

  const double vertices = double(m.vertex_count()), texels = double(texel.covered);
  const double v_direct = vertex.seconds_visibility / vertices, t_direct = (texel.bake.seconds_visibility + texel.seconds_raster +
                                                                            texel.seconds_repair) / texels;
  const double v_bounce = vertex.seconds_bounces / vertices, t_bounce = texel.bake.seconds_bounces / texels;
  std::printf("points: %.0f vertices, %.0f covered texels (%zu moved, %zu unrecoverable)\n", vertices, texels, texel.moved,
              texel.unrecoverable);
  std::printf("shadowed pass per point: vertex %.3f us, texel %.3f us (raster %.2f s, repair %.2f s, visibility %.2f s) -> ratio %.3f "
              "(target <= 1.25)\n",
              1e6 * v_direct, 1e6 * t_direct, texel.seconds_raster, texel.seconds_repair, texel.bake.seconds_visibility, t_direct / v_direct);
  std::printf("bounce pass per point:   vertex %.3f us, texel %.3f us -> ratio %.3f (target <= 1.5)\n", 1e6 * v_bounce, 1e6 * t_bounce,
              t_bounce / v_bounce);
  std::printf("whole bake per point:    vertex %.3f us, texel %.3f us -> ratio %.3f\n", 1e6 * vertex_total / vertices,
              1e6 * texel_total / texels, (texel_total / texels) / (vertex_total / vertices));
  return 0;
}
