#pragma once
// `prt bake --lightmap ... --gltf OUT.glb`: the mesh with its texel transfer as KTX2 float16 textures
// (docs/formats.md, "Lightmap transfer in glTF").
#include <string>

#include "mesh/mesh.h"
#include "transfer/transfer_file.h"

namespace prt::cli {

/// Writes `path` (atomically) from the mesh the transfer was baked for (with its lightmap UVs) and the
/// texel transfer: transfer::lightmap_ktx2_textures as images, transfer::lightmap_extension_json on the
/// primitive, mesh::write_glb_textured. Throws prt::Error naming the file or the problem.
void write_lightmap_glb(const std::string& path, const mesh::Mesh& mesh, const transfer::TransferData& transfer);

}  // namespace prt::cli
