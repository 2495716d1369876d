#pragma once
// Scenes of named parts for the mixed (texel + vertex) bake tests, and a glTF writer that keeps the
// parts apart (one node, mesh and primitive each), so that `prt bake --texel-parts NAME` can choose them.
#include <string>
#include <vector>

#include "mesh/mesh.h"

namespace prt::test {

/// A named run of triangles of a mesh.
struct NamedPart {
  std::string name;
  std::size_t first_triangle = 0, triangle_count = 0;
};

/// The box on a floor of floor_and_box(true) (lightmap_scenes.h) plus a back wall at z = +1 (x in
/// [-1, 1], y in [0, 0.6], facing -z, chart [0.81, 0.99] x [0.01, 0.59]), as parts "Floor" (2
/// triangles), "Box" (12) and "Wall" (2), in that order. Without the box if !with_box.
mesh::Mesh room_with_box(bool with_box, std::vector<NamedPart>& parts);

/// Writes `mesh` as a .gltf with a .bin beside it: per part one node named part.name with one mesh of
/// one primitive: POSITION, NORMAL, TEXCOORD_0 (the lightmap UVs, glTF's v-down as Mesh keeps them) and
/// indices. Each vertex's UV is that of its first corner (the meshes here are unwelded per chart).
void write_gltf_parts(const std::string& path, const mesh::Mesh& mesh, const std::vector<NamedPart>& parts);

}  // namespace prt::test
