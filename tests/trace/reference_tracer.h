#pragma once
// A slow, obviously-correct ray tracer for checking prt::trace on tiny scenes: every triangle is tested
// with the Moller-Trumbore algorithm in double precision (Moller & Trumbore 1997, "Fast, minimum
// storage ray-triangle intersection"). Two-sided, like Embree without backface culling.
#include <cmath>
#include <cstdint>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <limits>

#include "mesh/mesh.h"

namespace prt::trace::testing {

struct ReferenceHit {
  std::uint32_t prim_id = 0xFFFFFFFFu;
  double t = std::numeric_limits<double>::infinity();
  double u = 0.0, v = 0.0;
  /// How close the hit point came to the triangle's boundary, as the smallest barycentric (u, v or
  /// 1-u-v) of the closest hit; how far (in the same units) the nearest other hit was behind it.
  double edge_margin = 0.0;
  double t_gap = std::numeric_limits<double>::infinity();
  bool hit() const { return prim_id != 0xFFFFFFFFu; }
};

/// Moller-Trumbore: t, u, v of the ray o + t d against triangle (p0, p1, p2), with
/// point = (1-u-v) p0 + u p1 + v p2 (Embree's parametrisation). False if parallel or outside.
inline bool intersect_triangle(const glm::dvec3& o, const glm::dvec3& d, const glm::dvec3& p0, const glm::dvec3& p1,
                               const glm::dvec3& p2, double& t, double& u, double& v) {
  const glm::dvec3 e1 = p1 - p0, e2 = p2 - p0;
  const glm::dvec3 pv = glm::cross(d, e2);
  const double det = glm::dot(e1, pv);
  if (det == 0.0) return false;
  const double inv = 1.0 / det;
  const glm::dvec3 tv = o - p0;
  u = glm::dot(tv, pv) * inv;
  if (u < 0.0 || u > 1.0) return false;
  const glm::dvec3 qv = glm::cross(tv, e1);
  v = glm::dot(d, qv) * inv;
  if (v < 0.0 || u + v > 1.0) return false;
  t = glm::dot(e2, qv) * inv;
  return true;
}

/// Closest hit with t in [tnear, tfar] over all triangles of `mesh` (positions taken as exact).
inline ReferenceHit reference_closest_hit(const mesh::Mesh& mesh, const glm::dvec3& o, const glm::dvec3& d,
                                          double tnear, double tfar) {
  ReferenceHit best;
  double second_t = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    double t, u, v;
    if (!intersect_triangle(o, d, glm::dvec3(mesh.positions[mesh.indices[i]]),
                            glm::dvec3(mesh.positions[mesh.indices[i + 1]]),
                            glm::dvec3(mesh.positions[mesh.indices[i + 2]]), t, u, v))
      continue;
    if (t < tnear || t > tfar) continue;
    if (t < best.t) {
      second_t = best.t;
      best.prim_id = static_cast<std::uint32_t>(i / 3);
      best.t = t;
      best.u = u;
      best.v = v;
      best.edge_margin = std::fmin(std::fmin(u, v), 1.0 - u - v);
    } else if (t < second_t) {
      second_t = t;
    }
  }
  best.t_gap = second_t - best.t;
  return best;
}

/// Whether any triangle meets the ray within [tnear, tfar].
inline bool reference_occluded(const mesh::Mesh& mesh, const glm::dvec3& o, const glm::dvec3& d, double tnear,
                               double tfar) {
  for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    double t, u, v;
    if (intersect_triangle(o, d, glm::dvec3(mesh.positions[mesh.indices[i]]),
                           glm::dvec3(mesh.positions[mesh.indices[i + 1]]),
                           glm::dvec3(mesh.positions[mesh.indices[i + 2]]), t, u, v) &&
        t >= tnear && t <= tfar)
      return true;
  }
  return false;
}

}  // namespace prt::trace::testing
