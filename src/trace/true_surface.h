#pragma once
// The true-surface rule (docs/conventions.md "Directions below the true surface"), the one place that
// decides what a direction on the wrong side of a triangle's own plane carries. Used alike by the
// reference path tracer (src/reference), the bake's passes (through trace/vertex_rays.h: src/bake,
// src/lightmap) and anything else that integrates about an interpolated (shading) normal at a point
// that lies on one triangle.
//
// At a point on a triangle with unit geometric normal ng, integrating the cosine lobe about the unit
// shading normal n (interpolated, so it may tilt away from ng):
//   - a direction w with ng . w <= 0 carries NO light: it points into the surface the point lies on
//     (traced, it would hit that surface a tiny distance away, or slip past a nearby edge);
//   - the surface's reflectance there is divided by kappa = (1 + n . ng) / 2, the share of the cosine
//     lobe about n (projected solid angle, pi) that lies above the plane ng . w = 0: the plane cuts the
//     unit disc of projected directions along a half ellipse of semi-axes 1 and n . ng, leaving
//     pi (1 + n . ng) / 2. So a white Lambertian surface under a uniform white sky still reflects
//     exactly 1, and a convex object, which cannot light itself, gains nothing from bounces.
// A mesh vertex is not a point on one triangle: the rule does not apply there (TrueSurface{}); its rays
// leave lifted along the vertex normal, which on a convex mesh never re-enters (trace/scene.h).
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "mesh/mesh.h"
#include "mesh/vertex_footprint.h"

namespace prt::trace {

/// The rule at one surface point. Default: no rule (a mesh vertex): every direction counts, scale 1.
struct TrueSurface {
  glm::dvec3 geometric_normal{0.0};  ///< unit normal of the point's triangle; zero: no rule
  double scale = 1.0;                ///< 1 / kappa, applied to the reflectance; 0 where kappa = 0

  /// Whether direction w (any length) may carry light: true without a rule, else ng . w > 0.
  bool admits(const glm::dvec3& w) const {
    return geometric_normal == glm::dvec3(0.0) || glm::dot(geometric_normal, w) > 0.0;
  }
};

/// The rule at a point of a triangle with unit geometric normal `ng`, integrating about unit shading
/// normal `n`: scale = 2 / (1 + n . ng), 0 where n . ng <= -1 (nothing of the lobe is above the plane).
inline TrueSurface true_surface(const glm::dvec3& n, const glm::dvec3& ng) {
  TrueSurface s;
  s.geometric_normal = ng;
  const double kappa = 0.5 * (1.0 + glm::dot(n, ng));
  s.scale = kappa > 0.0 ? 1.0 / kappa : 0.0;
  return s;
}

/// Unit geometric normal of mesh triangle t, (p1 - p0) x (p2 - p0) of its counter-clockwise corners,
/// in double; zero for a degenerate triangle.
inline glm::dvec3 triangle_normal(const mesh::Mesh& mesh, std::uint32_t t) {
  const std::uint32_t* tri = mesh.indices.data() + 3 * static_cast<std::size_t>(t);
  const glm::dvec3 p0(mesh.positions[tri[0]]);
  const glm::dvec3 c = glm::cross(glm::dvec3(mesh.positions[tri[1]]) - p0, glm::dvec3(mesh.positions[tri[2]]) - p0);
  const double length = glm::length(c);
  return length > 0.0 ? c / length : glm::dvec3(0.0);
}

/// The rule at a point of mesh triangle t with shading normal n (the vertex normal of a footprint
/// point, the interpolated normal of a hit or texel); no rule for t = mesh::kNoTriangle or a
/// degenerate triangle.
inline TrueSurface true_surface(const mesh::Mesh& mesh, std::uint32_t t, const glm::dvec3& n) {
  if (t == mesh::kNoTriangle) return TrueSurface{};
  const glm::dvec3 ng = triangle_normal(mesh, t);
  return ng == glm::dvec3(0.0) ? TrueSurface{} : true_surface(glm::normalize(n), ng);
}

}  // namespace prt::trace
