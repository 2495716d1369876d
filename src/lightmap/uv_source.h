#pragma once
// Which lightmap UVs a texel bake uses (`prt bake --lightmap SIZE --uv MODE`; docs/conventions.md,
// "Generated lightmap UVs"):
//   file      the file's (TEXCOORD_1, else TEXCOORD_0; OBJ vt; PLY u, v), checked and refused as
//             uv_validation.h says (the default: the transfer then matches the input mesh file);
//   auto      the file's when uv_validation.h accepts them (a few defects repaired or skipped), else
//             generated: no UVs, tiling texture UVs, or defects beyond its rule;
//   generate  always generated.
// Generated UVs (src/unwrap) are packed for the bake's lightmap size with a padding of max(1, gutter)
// texels, so that the gutters of two charts never meet.
#include <string>

#include "lightmap/texel_bake.h"
#include "mesh/mesh.h"
#include "unwrap/unwrap.h"

namespace prt::lightmap {

enum class UvMode { file, automatic, generate };

/// Parses "file", "auto" or "generate"; throws prt::OptionError("uv ...") for anything else.
UvMode parse_uv_mode(const std::string& text);

struct UvSourceReport {
  bool generated = false;
  std::string reason;             ///< why they were generated ("--uv generate", the refusal, the missing-UV reason)
  unwrap::UnwrapReport unwrap;    ///< when generated
};

/// Gives `mesh` the lightmap UVs the bake uses (see above): when generated, Mesh::lightmap_uv is
/// replaced and lightmap_uv_set set to 1 (the set `prt unwrap` writes). `lightmap` gives the size,
/// gutter and mesh path (for messages), `missing_uv_reason` of the load report included; a mixed
/// scene's lightmap.vertex_triangles (part_choice.h, chosen on the file's UVs) are left out of auto's
/// judgement, as the bake's UV checks leave them out (their UVs are never read). Deterministic for any
/// `threads`.
void choose_lightmap_uvs(mesh::Mesh& mesh, UvMode mode, const LightmapOptions& lightmap, int threads, UvSourceReport* report = nullptr);

}  // namespace prt::lightmap
