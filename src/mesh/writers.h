#pragma once
// Mesh output files: colour PLYs (per-vertex radiance, `prt render --ply`, read back by `prt compare`)
// and glTF 2.0 binaries (.glb) carrying baked transfer coefficients as custom vertex attributes.
// Both are written atomically (prt::AtomicFile): the target never exists half-written.
//
// COLOUR PLY LAYOUT (write_ply): binary little-endian PLY 1.0,
//   element vertex N: float x, float y, float z [, float red, float green, float blue]
//   element face F:   list uchar int vertex_indices (always 3)
// Colours are linear, unclamped floats (radiance, not 8-bit sRGB), so values above 1 survive.
//
// GLB LAYOUT (write_glb): one scene, one node (no transform), one mesh, one triangle primitive
// (mode 4, no material), one buffer in the GLB BIN chunk. Attributes, each its own tightly packed
// buffer view (target ARRAY_BUFFER) at a 4-byte aligned offset, in this order:
//   POSITION vec3 float (accessor min/max set), NORMAL vec3 float (if the mesh has normals),
//   COLOR_0 vec3 float (if given: the radiance tone-mapped to [0, 1) by Reinhard's x / (1 + x) per
//   channel, since glTF requires COLOR_0 in [0, 1]) followed by "_PRT_RADIANCE" vec3 float (the linear,
//   unclamped radiance itself), then each extra attribute as vec4 float in the order given,
//   then the indices: scalar unsigned int (target ELEMENT_ARRAY_BUFFER).
// Extra attribute names are application-specific semantics: they start with '_' and use only
// A-Z, 0-9 and '_' (e.g. "_PRT_T0", "_PRT_T1", ...: the baker packs 4 transfer coefficients each).
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "mesh/mesh.h"

namespace prt::mesh {

/// Writes a binary little-endian PLY with positions, optional linear float colours (empty: no colour
/// properties) and triangles. Preconditions (else prt::Error naming `path`): colours empty or one per
/// position; indices.size() % 3 == 0; every index < positions.size() <= 2^31 - 1.
void write_ply(const std::string& path, const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& colours,
               const std::vector<std::uint32_t>& indices);

/// A colour PLY as read back by read_ply_colours: raw values, nothing converted.
struct ColourPly {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> colours;      ///< red, green, blue exactly as stored (float or double)
  std::vector<std::uint32_t> indices;  ///< fan-triangulated faces; empty if the file has none
};

/// Reads a PLY (any encoding) whose vertices have float or double red/green/blue, returning the raw
/// colour values (partner of write_ply; `prt compare` compares these). Throws prt::Error
/// ("<path>: <problem>") for unreadable, malformed or truncated files and for files without float
/// colours (8-bit colours are refused: they are not radiance).
ColourPly read_ply_colours(const std::string& path);

/// An application-specific vec4 float vertex attribute for write_glb.
struct VertexAttribute {
  std::string name;               ///< e.g. "_PRT_T0": '_' then A-Z, 0-9, '_'
  std::vector<glm::vec4> values;  ///< one per vertex
};

/// Writes `mesh` (positions, normals if any, indices) as a glTF 2.0 binary with the layout above, plus
/// COLOR_0 = x / (1 + x) and _PRT_RADIANCE = x from the linear radiance `colour_0` (empty for none) and `extra_attributes`. Albedo is not written.
/// Throws prt::Error naming `path` if an attribute's length differs from the vertex count, a name is
/// not a valid application-specific semantic (or repeats), the mesh is empty, or writing fails.
void write_glb(const std::string& path, const Mesh& mesh, const std::vector<VertexAttribute>& extra_attributes,
               const std::vector<glm::vec3>& colour_0 = {});

/// An image stored in a GLB's BIN chunk: a glTF "images" entry with a bufferView and mimeType.
struct GlbImage {
  std::string bytes;
  std::string mime_type;  ///< e.g. "image/ktx2"
};

/// Writes `mesh` with its lightmap UVs (Mesh::lightmap_uv, one per corner) as a glTF 2.0 binary: the
/// GLB layout above without COLOR_0 and extra attributes, except that the vertices are split by UV:
/// one vertex per distinct (mesh vertex, corner UV) pair, in order of first use by the corners, with
/// POSITION, NORMAL (if the mesh has normals) and TEXCOORD_0 = the lightmap UV as Mesh keeps it (glTF's
/// convention), then the indices, then each of `images` as a buffer view and a glTF image (in order:
/// image i is `images[i]`). The primitive gets extensions[extension_name] = `extension_json` (a JSON
/// object, which refers to the images by index); extension_name is listed in extensionsUsed, not in
/// extensionsRequired (an engine without it still loads the mesh). Throws prt::Error naming `path` for
/// a mesh write_glb refuses, a mesh without lightmap UVs or with a non-finite one, an extension that is
/// not a JSON object, or a failed write.
void write_glb_textured(const std::string& path, const Mesh& mesh, const std::vector<GlbImage>& images,
                        const std::string& extension_name, const std::string& extension_json);

/// Writes `mesh` with its lightmap UVs as a glTF 2.0 binary for engines and for prt (`prt unwrap`):
/// the layout of write_glb_textured (vertices split by UV, POSITION, NORMAL if any) with the UVs as
/// TEXCOORD_1 (the set load_mesh reads as lightmap UVs first), no images, no extension, no materials.
/// Throws prt::Error naming `path` as write_glb_textured does.
void write_glb_lightmap_uv(const std::string& path, const Mesh& mesh);

}  // namespace prt::mesh
