#pragma once
// The files a bake writes (docs/formats.md): its transfer as a .prt file, or clustered-PCA compressed as
// a .cprt file, and optionally the mesh with the transfer as a glTF binary (per vertex: vertex
// attributes; per texel: KTX2 float16 textures). What `prt bake` runs after bake::bake or
// lightmap::bake_lightmap.
#include <string>

#include "mesh/mesh.h"
#include "transfer/transfer_file.h"

namespace prt::pipeline {

struct TransferOutputs {
  std::string transfer_path;  ///< .prt, or .cprt when clusters > 0; required
  std::string gltf_path;      ///< .glb of the mesh with its transfer; empty: none
  std::string source_path;    ///< the mesh file the mesh was loaded from (the glTF keeps its scene)
  bool float16 = false;       ///< store the transfer (or the compressed model) as IEEE float16
  int clusters = 0, pca = 0;  ///< > 0: compress with CPCA, `clusters` clusters of `pca` vectors each
  unsigned seed = 1;          ///< of the compression's initial clusters
  int threads = 0;            ///< for the compression (0 = all cores); the output does not depend on it
};

/// Writes `transfer` (baked for `mesh`) to the outputs, each through its temporary, and commits them
/// together: a failing second output leaves no first one. The compression runs in the shaded metric
/// with no lighting, as `prt compress` without --env does. Glossy transfer has no glTF form. A per-vertex
/// glTF is the engine glTF (engine_export.h) of `source_path` with the .cprt's model, or without
/// --compress a model of the export's default settings.
/// Throws prt::Error naming the file, or OptionError for clusters or pca out of range.
void write_transfer_outputs(const mesh::Mesh& mesh, transfer::TransferData transfer, const TransferOutputs& outputs);

/// Writes `path` (atomically): the mesh the texel transfer was baked for (with its lightmap UVs) and
/// the transfer as KTX2 float16 textures under the PRT_lightmap_transfer extension (docs/formats.md,
/// "Lightmap transfer in glTF"). Throws prt::Error naming the file or the problem.
void write_lightmap_glb(const std::string& path, const mesh::Mesh& mesh, const transfer::TransferData& transfer);

}  // namespace prt::pipeline
