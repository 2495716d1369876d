#pragma once
// The engine glTF of a bake (docs/formats.md, "The engine glTF: PRT_transfer"): the source mesh file as
// authored with the transfer in clustered-PCA form: per vertex _PRT_CLUSTER (SCALAR float),
// _PRT_WEIGHTS0.. (VEC4 float, the PCA weights zero-padded), _PRT_ALBEDO (VEC3, the albedo baked into the
// vertex's transfer, which the discs' direct light takes); per texel a KTX2 cluster texture (cluster,
// coverage) and weights texture array, and _PRT_ALBEDO per vertex as well;
// per model the cluster means and directions as float accessors under the root extension PRT_transfer.
#include <cstdint>
#include <string>
#include <vector>

#include "compress/compressed.h"
#include "mesh/mesh.h"

namespace prt::pipeline {

/// The vendor extension's name, in extensionsUsed (not extensionsRequired).
inline constexpr const char* kTransferExtension = "PRT_transfer";
/// The CPCA settings an export compresses an uncompressed transfer with: K = min(this, points: vertices
/// or non-empty texels) clusters, N = min(this, values per point) PCA vectors.
inline constexpr int kExportClusters = 64;
inline constexpr int kExportPca = 8;

/// Writes `path` (atomically): `source_path`, the mesh file `mesh` was loaded from, as an engine glTF
/// carrying `model` (diffuse: unshadowed, shadowed or interreflected; per vertex or per texel; its source
/// header matching the mesh). The albedo attribute is shade::surface_albedo's. Throws prt::Error naming
/// the file for a glossy model, a model of another mesh, or what mesh::write_engine_glb refuses.
/// `uv_generated`: the mesh's lightmap UVs were generated, not read from the source; the file carries
/// them (mesh::EngineExtras::corner_uvs).
void write_engine_gltf(const std::string& path, const std::string& source_path, const mesh::Mesh& mesh,
                       const compress::CompressedTransfer& model, bool uv_generated = false);

/// Writes `path` (atomically): the engine glTF of a mixed scene (docs/formats.md, "Mixed scenes in the
/// engine glTF"): `source_path` with model 0 `texels` (per texel) on the primitives whose triangles
/// are all per texel and model 1 `vertices` (per vertex, every mesh vertex) on those whose triangles
/// are all per vertex (`vertex_triangle`: per triangle of `mesh`, 1 per vertex), _PRT_ALBEDO on both.
/// Throws prt::Error naming the file for models of another mesh or kind, a primitive with triangles of
/// both kinds, or what mesh::write_engine_glb refuses.
void write_mixed_engine_gltf(const std::string& path, const std::string& source_path, const mesh::Mesh& mesh,
                             const compress::CompressedTransfer& texels, const compress::CompressedTransfer& vertices,
                             const std::vector<std::uint8_t>& vertex_triangle);

}  // namespace prt::pipeline
