#pragma once
// The files a bake writes (docs/formats.md): its transfer as a .prt file, or clustered-PCA compressed as
// a .cprt file, and optionally the engine glTF (the source scene with the transfer's CPCA model: per
// vertex in vertex attributes, per texel in KTX2 float16 textures). What `prt bake` runs after bake::bake or
// lightmap::bake_lightmap.
#include <string>

#include "compress/compressed.h"
#include "mesh/mesh.h"
#include "sh/coefficients.h"
#include "transfer/transfer_file.h"

namespace prt::pipeline {

struct TransferOutputs {
  std::string transfer_path;  ///< .prt, or .cprt when clusters > 0; required
  std::string gltf_path;      ///< .glb of the mesh with its transfer; empty: none
  std::string source_path;    ///< the mesh file the mesh was loaded from (the glTF keeps its scene)
  bool uv_generated = false;  ///< the lightmap UVs are not the source's (prt bake --uv): the glTF is the mesh as loaded
  bool float16 = false;       ///< store the transfer (or the compressed model) as IEEE float16
  int clusters = 0, pca = 0;  ///< > 0: compress with CPCA, `clusters` clusters of `pca` vectors each
  unsigned seed = 1;          ///< of the compression's initial clusters
  std::size_t fit_points = 0; ///< compression: fit the rounds on this many points (compress::CpcaOptions::fit_points); 0: all
  int rounds = 20;            ///< compression: most CPCA rounds (compress::CpcaOptions::iterations)
  const sh::RgbCoefficients* metric_sky = nullptr;  ///< compression: the metric's spectrum (null: flat; shaded_compression.h)
  int threads = 0;            ///< for the compression (0 = all cores); the output does not depend on it
};

/// The CPCA model of `transfer` that the .cprt file and the engine glTF carry: `outputs`' clusters and
/// pca when set, else the export's defaults (engine_export.h: K = min(64, points), N = min(8, values
/// per point)); in the shaded metric of outputs.metric_sky. Throws as write_transfer_outputs does.
compress::CompressedTransfer transfer_model(const transfer::TransferData& transfer, const TransferOutputs& outputs);

/// Writes `transfer` (baked for `mesh`) to the outputs, each through its temporary, and commits them
/// together: a failing second output leaves no first one. The compression runs in the shaded metric
/// with no lighting, as `prt compress` without --env does. Glossy transfer has no glTF form. The glTF is
/// the engine glTF (engine_export.h, per vertex or per texel) of `source_path` with the .cprt's model,
/// or without --compress a model of the export's default settings.
/// Throws prt::Error naming the file, or OptionError for clusters or pca out of range.
void write_transfer_outputs(const mesh::Mesh& mesh, transfer::TransferData transfer, const TransferOutputs& outputs);

}  // namespace prt::pipeline
