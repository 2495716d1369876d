#pragma once
// Least-squares conformal maps (Lévy, Petitjean, Ray and Maillot, "Least squares conformal maps for
// automatic texture atlas generation", SIGGRAPH 2002): the UVs of a chart that make each triangle's
// map as close to a similarity as possible in the least-squares sense. Each triangle T, in its own
// orthonormal frame with corners p0, p1, p2 (complex numbers), adds the complex residual
//   sum_j W_j U_j / sqrt(2 area_T),  W_j = p_{j+2} - p_{j+1} (indices mod 3),
// which is zero exactly when the corners' UVs U_j are a rotation and scaling of p_j (orientation kept).
// Two vertices are pinned (the two extremes of the chart along the longest side of its projection on
// the plane of its mean normal, at their projected positions); the normal equations of the remaining
// unknowns are solved with Eigen's sparse LDLT (SimplicialLDLT). A chart's vertices are its corners'
// welded vertices (charts.h), so a position on a border between charts gets one UV per chart.
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

#include "mesh/mesh.h"
#include "unwrap/charts.h"

namespace prt::unwrap {

/// A flattened chart: its triangles and, per triangle in that order, 3 corner UVs (corner_uv[3i + k]
/// for corner k of triangles[i]) in world units: scaled so that the UV area equals the 3D area.
struct FlatChart {
  std::vector<std::uint32_t> triangles;
  std::vector<glm::dvec2> corner_uv;
};

/// LSCM of a connected chart (connected_pieces). Returns false (corner_uv unspecified) when the
/// linear system is singular (no two distinct pins) or the solution is not finite; the caller checks
/// folds and overlaps (embedding.h). Deterministic.
bool lscm_chart(const mesh::Mesh& mesh, const Surface& surface, FlatChart& chart);

/// Orthogonal projection of the chart on the plane of its area-weighted mean face normal (a fallback
/// for small pieces). Always succeeds; may fold when the piece is not a height field over that plane.
void planar_chart(const mesh::Mesh& mesh, FlatChart& chart);

/// Scales corner_uv so that its total UV area equals the chart's 3D area, mirroring u first when the
/// signed UV area is negative. A chart of zero UV area is left as it is.
void normalize_area(const mesh::Mesh& mesh, FlatChart& chart);

}  // namespace prt::unwrap
