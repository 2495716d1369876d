#pragma once
// Triangle meshes as prt bakes and renders them.
//
// VERTEX ORDER: a loaded mesh's vertices map 1:1, in order, to the input file's vertices (engines load
// baked per-vertex data onto their own copy of the mesh): OBJ "v" lines, PLY "vertex" elements, glTF
// primitives' vertices in the order documented in docs/formats.md. Nothing is welded or reordered.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace prt::mesh {

struct Mesh {
  std::vector<glm::vec3> positions;   ///< in the file's units and frame (glTF: node transforms applied)
  std::vector<glm::vec3> normals;     ///< unit length, one per vertex
  std::vector<glm::vec3> albedo;      ///< linear diffuse reflectance in [0,1] per vertex; empty if none given
  std::vector<std::uint32_t> indices; ///< 3 per triangle, counter-clockwise front faces; degenerate removed
};

/// What loading found, for messages and tests.
struct LoadReport {
  std::size_t skipped_degenerate = 0;  ///< triangles dropped: repeated index or zero area
  bool normals_computed = false;       ///< the file had no (usable) normals: area-weighted ones computed
  bool albedo_from_file = false;       ///< albedo came from materials or vertex colours
};

/// Loads .obj (+ .mtl Kd), .ply (ASCII / binary, optional red/green/blue), .gltf / .glb (every mesh
/// primitive of the default scene, node transforms, baseColorFactor and COLOR_0 as albedo).
/// Throws prt::Error("<path>: <problem>") for: unreadable file, unsupported format, NaN/Inf positions,
/// indices out of range, no triangles left. Prints one line on stderr when normals are computed or
/// triangles are skipped (unless `quiet`).
Mesh load_mesh(const std::string& path, LoadReport* report = nullptr, bool quiet = false);

/// Area-weighted vertex normals (unit; +Y for vertices of no triangle).
std::vector<glm::vec3> area_weighted_normals(const std::vector<glm::vec3>& positions,
                                             const std::vector<std::uint32_t>& indices);

/// 64-bit fingerprint of positions and indices (bit patterns, FNV-1a), stored in transfer files so a
/// reader can tell that a file belongs to a mesh.
std::uint64_t fingerprint(const Mesh& mesh);

/// Axis-aligned bounds.
struct Bounds {
  glm::vec3 lo{0.0f}, hi{0.0f};
  float diagonal() const;
};
Bounds bounds(const Mesh& mesh);

}  // namespace prt::mesh
