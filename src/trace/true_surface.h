#pragma once
// The true-surface rule (docs/conventions.md "Directions below the true surface"), the one place that
// decides what a direction on the wrong side of a triangle's own plane carries. Used alike by the
// reference path tracer (src/reference) and, through trace/vertex_rays.h, by every pass of the bakes
// (src/bake, src/lightmap).
//
// At a point that lies on one triangle (a path tracer's hit, a vertex footprint point, a lightmap
// texel sample), integrating about an interpolated (shading) normal n that may tilt away from the
// triangle's geometric normal ng: a direction w with ng . w <= 0 carries NO light. It points into the
// surface the point lies on; traced, it would hit that surface a tiny distance away (and gather its
// light in a bounce) or slip past a nearby edge. Nothing renormalises the rest of the lobe: a point
// whose shading normal tilts by theta loses the share (1 - cos theta) / 2 of its cosine lobe, as in a
// path tracer that tests the geometric side.
// A mesh vertex is not a point on one triangle: the rule does not apply there (TrueSurface{}); its rays
// leave lifted along the vertex normal, which on a convex mesh never re-enters (trace/scene.h).
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "mesh/mesh.h"
#include "mesh/vertex_footprint.h"

namespace prt::trace {

/// The rule at one surface point. Default: no rule (a mesh vertex): every direction counts.
struct TrueSurface {
  glm::dvec3 geometric_normal{0.0};  ///< unit normal of the point's triangle; zero: no rule

  /// Whether direction w (any length) may carry light: true without a rule, else ng . w > 0.
  bool admits(const glm::dvec3& w) const {
    return geometric_normal == glm::dvec3(0.0) || glm::dot(geometric_normal, w) > 0.0;
  }
};

/// Unit geometric normal of mesh triangle t, (p1 - p0) x (p2 - p0) of its counter-clockwise corners,
/// in double; zero for a degenerate triangle.
inline glm::dvec3 triangle_normal(const mesh::Mesh& mesh, std::uint32_t t) {
  const std::uint32_t* tri = mesh.indices.data() + 3 * static_cast<std::size_t>(t);
  const glm::dvec3 p0(mesh.positions[tri[0]]);
  const glm::dvec3 c = glm::cross(glm::dvec3(mesh.positions[tri[1]]) - p0, glm::dvec3(mesh.positions[tri[2]]) - p0);
  const double length = glm::length(c);
  return length > 0.0 ? c / length : glm::dvec3(0.0);
}

/// The rule at a point of mesh triangle t; no rule for t = mesh::kNoTriangle or a degenerate triangle.
inline TrueSurface true_surface(const mesh::Mesh& mesh, std::uint32_t t) {
  return t == mesh::kNoTriangle ? TrueSurface{} : TrueSurface{triangle_normal(mesh, t)};
}

}  // namespace prt::trace
