#pragma once
// Counting how the traced occlusion answers of vertex rays differ from the exact answer (test_offset.cpp,
// test_robust.cpp). The exact answer is the double-precision brute-force tracer (reference_tracer.h)
// from p + n * 1e-9 D (far above double rounding, far below any feature; D the bounding-box diagonal),
// which is "occluded iff something really blocks the ray leaving the surface" (docs/conventions.md,
// "Ray offset").
#include <cmath>
#include <cstddef>
#include <string>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "bench_meshes.h"
#include "core/parallel.h"
#include "mesh/mesh.h"
#include "trace/reference_tracer.h"
#include "trace/scene.h"

namespace prt::trace::testing {

/// Directions about +Z for the vertex tests: `count` uniform hemisphere directions and 8 grazing ones
/// with d.n = 1e-3.
inline std::vector<glm::vec3> test_directions(std::size_t count) {
  std::vector<glm::vec3> dirs = bench::hemisphere_directions(count);
  for (int g = 0; g < 8; ++g) {
    const double phi = 0.785 * g + 0.1, z = 1e-3, r = std::sqrt(1.0 - z * z);
    dirs.push_back(glm::vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z)));
  }
  return dirs;
}

/// Direction k of vertex v in world space: the set rotated into v's frame, twisted about n by a
/// per-vertex angle so that neighbouring vertices do not share directions.
inline glm::vec3 vertex_direction(const mesh::Mesh& m, std::size_t v, const glm::vec3& local) {
  glm::vec3 t, b;
  const glm::vec3 n = m.normals[v];
  bench::orthonormal_frame(n, t, b);
  const double twist = 2.399963 * double(v);
  const float c = float(std::cos(twist)), s = float(std::sin(twist));
  const glm::vec3 l(c * local.x - s * local.y, s * local.x + c * local.y, local.z);
  return glm::normalize(t * l.x + b * l.y + n * l.z);
}

inline double diagonal(const trace::Scene& scene) {
  return glm::length(glm::dvec3(scene.bounds_hi()) - glm::dvec3(scene.bounds_lo()));
}

/// Where a test ray of vertex v starts and from which t it counts: either the scene's own rule
/// (Scene::spawn_point, `own_rule`) or an alternative: origin p + n * lift - d * pullback, tnear.
struct Spawn {
  bool own_rule = true;
  float lift = 0.0f, pullback = 0.0f, tnear = 0.0f;
};

/// Fills `batch` with the rays of vertex v along `dirs` (cleared first).
inline void push_vertex_rays(const trace::Scene& scene, const mesh::Mesh& m, std::size_t v,
                             const std::vector<glm::vec3>& dirs, const Spawn& spawn, trace::RayBatch& batch) {
  batch.clear();
  const glm::vec3 p = m.positions[v], n = m.normals[v];
  const trace::SpawnPoint own = scene.spawn_point(p, n);
  batch.set_robust(spawn.own_rule && own.robust);
  for (const glm::vec3& l : dirs) {
    const glm::vec3 d = vertex_direction(m, v, l);
    if (spawn.own_rule) batch.push(own.origin, d);
    else batch.push(p + n * spawn.lift - d * spawn.pullback, d, spawn.tnear);
  }
}

/// Exact answer of ray k of vertex v.
inline bool exact_ray(const mesh::Mesh& m, std::size_t v, const glm::vec3& local, double D) {
  const glm::dvec3 o = glm::dvec3(m.positions[v]) + glm::dvec3(m.normals[v]) * (1e-9 * D);
  return reference_occluded(m, o, glm::dvec3(vertex_direction(m, v, local)), 0.0, 1e300);
}

/// Exact answers for every `stride`-th vertex and its test directions (vertex-major).
inline std::vector<char> exact_occlusion(const mesh::Mesh& m, const std::vector<glm::vec3>& dirs, double D,
                                         std::size_t stride) {
  const std::size_t vertices = (m.positions.size() + stride - 1) / stride;
  std::vector<char> exact(vertices * dirs.size());
  parallel_for(vertices, 8, 0, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      for (std::size_t k = 0; k < dirs.size(); ++k) exact[i * dirs.size() + k] = exact_ray(m, i * stride, dirs[k], D);
  });
  return exact;
}

/// A mesh of a printed study (test_trace "[.sweep]", "[.leaks]"): every `stride`-th vertex is traced.
struct StudyCase {
  std::string name;
  mesh::Mesh m;
  std::size_t stride = 1;
};

/// Disagreements with the exact answer.
struct Disagreements {
  std::size_t rays = 0, truly_occluded = 0;
  std::size_t self_hits = 0;  ///< occluded although nothing blocks the ray
  std::size_t leaks = 0;      ///< not occluded although something blocks it
};

/// Traced answers against `exact` (exact_occlusion with the same dirs and stride).
inline Disagreements compare(const trace::Scene& scene, const mesh::Mesh& m, const std::vector<glm::vec3>& dirs,
                             const std::vector<char>& exact, const Spawn& spawn, std::size_t stride) {
  Disagreements d;
  trace::RayBatch batch(dirs.size());
  for (std::size_t v = 0, i = 0; v < m.positions.size(); v += stride, ++i) {
    push_vertex_rays(scene, m, v, dirs, spawn, batch);
    scene.occluded(batch);
    for (std::size_t k = 0; k < dirs.size(); ++k) {
      const bool truth = exact[i * dirs.size() + k];
      ++d.rays;
      d.truly_occluded += truth;
      d.self_hits += batch.is_occluded(k) && !truth;
      d.leaks += !batch.is_occluded(k) && truth;
    }
  }
  return d;
}

/// Two tracings of the same rays from every vertex (scene a with spawn sa, scene b with spawn sb),
/// compared with the exact answer only where they differ: how many more self-hits and leaks b has than
/// a (negative: fewer), over all vertices. Cheap enough for whole meshes: the brute-force tracer runs
/// only on the rays whose answers differ.
struct Difference {
  std::size_t rays = 0, differing = 0;
  long long extra_self_hits = 0, extra_leaks = 0;
};

inline Difference compare_all(const trace::Scene& a, const Spawn& sa, const trace::Scene& b, const Spawn& sb,
                              const mesh::Mesh& m, const std::vector<glm::vec3>& dirs) {
  Difference diff;
  const double D = diagonal(a);
  trace::RayBatch ba(dirs.size()), bb(dirs.size());
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    push_vertex_rays(a, m, v, dirs, sa, ba);
    push_vertex_rays(b, m, v, dirs, sb, bb);
    a.occluded(ba);
    b.occluded(bb);
    diff.rays += dirs.size();
    for (std::size_t k = 0; k < dirs.size(); ++k) {
      if (ba.is_occluded(k) == bb.is_occluded(k)) continue;
      ++diff.differing;
      const bool truth = exact_ray(m, v, dirs[k], D);
      // b occluded, a not: b self-hits if nothing blocks, else a leaks.
      if (bb.is_occluded(k)) (truth ? diff.extra_leaks -= 1 : diff.extra_self_hits += 1);
      else (truth ? diff.extra_leaks += 1 : diff.extra_self_hits -= 1);
    }
  }
  return diff;
}

}  // namespace prt::trace::testing
