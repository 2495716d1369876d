#pragma once
// Lightmap charts: the connected pieces of a mesh's lightmap UV layout (docs/conventions.md, "Lightmap
// charts, denoising and seams"). Two triangles are in one chart when they share an edge in UV: both corners of the edge have
// bit-identical UVs in the two triangles (the mesh's vertex indices do not matter, so an unwelded mesh
// with a continuous UV layout is one chart). A UV seam (the same 3D edge at two places in the UV square)
// separates charts, and so does a chart border.
#include <cstdint>
#include <vector>

#include "mesh/mesh.h"

namespace prt::lightmap {

/// One chart id per triangle of `mesh` (which must have lightmap UVs), 0..count-1, numbered in the
/// order of each chart's lowest triangle index. Deterministic.
std::vector<std::uint32_t> triangle_charts(const mesh::Mesh& mesh);

/// The world size of one texel on each triangle of `mesh` in a width x height lightmap:
/// sqrt(3D area / UV area in texels), in the mesh's units; 0 for a triangle of zero UV area.
std::vector<float> texel_world_sizes(const mesh::Mesh& mesh, int width, int height);

}  // namespace prt::lightmap
