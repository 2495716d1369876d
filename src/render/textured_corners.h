#pragma once
// Internal to the renderer: the vertices of a textured mesh's indexed draw (base_colour.h). A textured
// vertex-stage run depends on its corner only through (mesh vertex, base-colour UV, material): corners
// that agree on all three (bit for bit) share one draw vertex, so the indexed draw runs the vertex stage
// about once per mesh vertex (plus one per UV seam or material border) instead of once per corner, and
// gives the rasteriser the same values the per-corner draw gave. No GL here.
#include <cstdint>
#include <vector>

#include "mesh/mesh.h"

namespace prt::render {

struct TexturedCorners {
  /// Per draw vertex: the first corner (3 t + k, in corner order) of the corners it stands for.
  std::vector<std::uint32_t> first_corner;
  /// Per corner (3 t + k): its draw vertex, in [0, first_corner.size()); the draw's index list.
  std::vector<std::uint32_t> draw_vertex;
};

/// The draw vertices of `mesh`: corners c and c' share one if indices, base_color_uv (the bits of
/// both floats) and triangle_material of their triangles are equal. Draw vertices are numbered in the
/// order of their first corner. Precondition: mesh.textured(), with base_color_uv and
/// triangle_material of mesh.h's sizes.
TexturedCorners textured_corners(const mesh::Mesh& mesh);

}  // namespace prt::render
