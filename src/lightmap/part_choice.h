#pragma once
// Which parts of a scene a lightmap bake bakes per texel and which per vertex (`prt bake --lightmap
// SIZE --texel-parts SPEC`; docs/conventions.md "Mixed scenes"). A part is a glTF triangle primitive
// as the loader visited it (Mesh::source_primitives: node, mesh, primitive); an OBJ or PLY file is one part,
// "mesh". SPEC:
//   all          every part per texel (the default: a plain lightmap bake);
//   auto         a part per texel when the lightmap gives it more texels than it has vertices (its UV
//                area times width x height exceeds its vertex count; triangles with UVs outside
//                [0, 1] count no area): large, coarse surfaces such as floors and walls get texels,
//                finely tessellated objects keep their vertices;
//   NAME[,NAME]  the parts whose node name is one of the NAMEs per texel (every part of that node),
//                the rest per vertex; a NAME may also be a part's whole description
//                ("node 3 \"Floor\" mesh 2 primitive 0").
#include <cstdint>
#include <string>
#include <vector>

#include "mesh/mesh.h"

namespace prt::lightmap {

struct PartChoice {
  std::vector<std::uint8_t> vertex_triangle;  ///< per triangle: 1 baked per vertex; all 0 for a plain bake
  std::vector<std::string> texel_parts, vertex_parts;  ///< descriptions, in part order
  /// True when some triangle is baked per vertex (the bake writes a mixed pair).
  bool mixed() const;
};

/// Chooses per texel or per vertex for every part of `mesh` (which has lightmap UVs) by `spec` and the
/// lightmap size. Throws prt::Error("<mesh_path>: --texel-parts: ...") in one line for a NAME no
/// part has (listing the names there are), names given for a file without named parts, an empty
/// NAME, a choice that leaves no part per texel, or (auto, names) a texel part without usable UVs (no
/// triangle of nonzero UV area inside [0, 1]).
PartChoice choose_parts(const mesh::Mesh& mesh, const std::string& spec, int width, int height, const std::string& mesh_path);

}  // namespace prt::lightmap
