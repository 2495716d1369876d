#pragma once
// What `prt bake --lightmap SIZE --texel-parts ...` writes for a mixed scene (docs/formats.md "Mixed
// transfer pairs"): the texel transfer file at the output path and the per-vertex transfer file beside
// it, each with the "mixed" entry (transfer/mixed_parts.h) naming the other, and with --gltf the engine
// glTF of the scene (engine_export.h, write_mixed_engine_gltf), committed together.
#include <cstdint>
#include <string>
#include <vector>

#include "mesh/mesh.h"
#include "transfer/mixed_parts.h"
#include "transfer/transfer_file.h"

namespace prt::pipeline {

/// The per-vertex file's path for a mixed bake written to `texel_path`: "<stem>.vertices.prt" in the
/// same folder ("room.prt" -> "room.vertices.prt").
std::string mixed_vertex_path(const std::string& texel_path);

struct MixedOutputs {
  std::string texel_path, vertex_path;  ///< the pair; required
  std::string gltf_path;                ///< the engine glTF; empty: none
  std::string gltf_source;              ///< the mesh file the glTF keeps (the file the bake's mesh was loaded from)
  std::vector<std::uint8_t> vertex_triangle;  ///< per triangle of the mesh: 1 baked per vertex
  std::vector<std::string> texel_parts, vertex_parts;  ///< the parts' descriptions
  bool float16 = false;  ///< store both files (and the glTF's models) as IEEE float16
  unsigned seed = 1;     ///< of the glTF models' compression
  int threads = 0;       ///< of the compression (0 = all cores); the output does not depend on it
};

/// Adds the "mixed" entries (texel and vertex parts' names, the per-vertex triangles) to both files'
/// parameters and writes them, and the engine glTF of `mesh` (both transfers CPCA-compressed with the
/// export's defaults, transfer_outputs.h transfer_model), each through its temporary, committing them
/// only when all are written (a failure leaves none). Throws prt::Error naming the file.
void write_mixed_outputs(const mesh::Mesh& mesh, transfer::TransferData texels, transfer::TransferData vertices, const MixedOutputs& outputs);

}  // namespace prt::pipeline
