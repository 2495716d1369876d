#pragma once
// Charts for lightmap UV generation (docs/conventions.md, "Generated lightmap UVs"): the mesh's
// triangles split into connected, disc-like regions that a planar map can flatten with low distortion.
//
// ADJACENCY. Vertices are welded by exact position (float bits), so meshes that repeat a position per
// face or per primitive still connect. An edge joins two triangles when exactly two triangles use it, in
// opposite directions (consistent winding), and both give its two endpoints the same vertex normal (to
// within kSmoothNormalDot): an authored normal split (a hard edge) cuts the surface. Edges of one
// triangle, or of three or more, are borders.
//
// GROWTH. Seeds are taken in triangle index order (the lowest unassigned triangle); a chart grows
// breadth-first over joined edges (neighbours in edge order 0, 1, 2 of each triangle) and takes a
// triangle only when its face normal lies within chart_angle of the seed's face normal: a
// chart's normals fit in a cone narrower than a hemisphere, so it never closes around a volume.
// Deterministic: no thread, no hash order.
#include <cstdint>
#include <vector>

#include "mesh/mesh.h"

namespace prt::unwrap {

/// Two vertex normals count as equal (a smooth edge) when their dot product is at least this.
inline constexpr double kSmoothNormalDot = 0.9999;

struct ChartOptions {
  double chart_angle = 60.0;  ///< cone half-angle of a chart's face normals about its seed's, (0, 89]
};

/// Throws prt::OptionError("chart_angle ...") unless 0 < chart_angle <= 89.
void check_chart_options(const ChartOptions& options);

/// The welded surface: per corner (3t + k) the welded vertex, and per corner the triangle across the
/// edge from corner k to corner (k + 1) % 3 (or kNoNeighbour).
struct Surface {
  std::vector<std::uint32_t> welded;     ///< per corner: welded vertex id (0..welded_count-1)
  std::vector<std::uint32_t> neighbour;  ///< per corner: triangle across edge (k, k+1), or kNoNeighbour
  std::uint32_t welded_count = 0;
};
inline constexpr std::uint32_t kNoNeighbour = 0xffffffffu;

/// Builds the adjacency described above. Precondition: mesh.normals has one normal per vertex.
Surface build_surface(const mesh::Mesh& mesh);

/// Unit face normal of triangle t (double; +Y for a zero-area triangle).
glm::dvec3 face_normal(const mesh::Mesh& mesh, std::size_t t);

/// Charts: each a list of triangles in the order they were added (seed first).
std::vector<std::vector<std::uint32_t>> make_charts(const mesh::Mesh& mesh, const Surface& surface,
                                                    const ChartOptions& options);

/// Splits `triangles` into the connected pieces that `surface` joins (pieces in order of their lowest
/// triangle's position in `triangles`, each piece's triangles in breadth-first order).
std::vector<std::vector<std::uint32_t>> connected_pieces(const Surface& surface, const std::vector<std::uint32_t>& triangles);

}  // namespace prt::unwrap
