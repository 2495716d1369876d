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

/// Writes `mesh` (positions, normals if any, indices) as a glTF 2.0 binary with the layout above, plus
/// COLOR_0 = x / (1 + x) and _PRT_RADIANCE = x from the linear radiance `colour_0` (empty for none).
/// Albedo is not written. Throws prt::Error naming `path` if `colour_0`'s length differs from the vertex
/// count, the mesh is empty, or writing fails.
void write_glb(const std::string& path, const Mesh& mesh, const std::vector<glm::vec3>& colour_0 = {});

/// An image stored in a GLB's BIN chunk: a glTF "images" entry with a bufferView and mimeType.
struct GlbImage {
  std::string bytes;
  std::string mime_type;  ///< e.g. "image/ktx2"
};

}  // namespace prt::mesh
