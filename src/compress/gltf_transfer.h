#pragma once
// Reading the engine glTF back (docs/formats.md, "The engine glTF: PRT_transfer"): its PRT_transfer
// model and per-vertex cluster, weights and albedo, as the CompressedTransfer of the mesh that
// mesh::load_mesh makes of the same file (its default scene).
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "compress/compressed.h"

namespace prt::compress {

/// Whether `path` starts as a glTF binary does ("glTF"); false for a file that cannot be read.
bool is_glb_file(const std::string& path);

/// The transfer of a prt engine glTF: model 0 of its PRT_transfer extension with the vertices of the
/// mesh load_mesh reads from `path` (its source header: that mesh's counts and fingerprint, the model's
/// kind, bands, channels and bake parameters, float32). *albedo gets _PRT_ALBEDO per vertex. Throws
/// prt::Error("<path>: <problem>") for a file without the extension, a malformed model (sizes, ranges,
/// a cluster index that is not an integer in [0, K), non-finite or too large values), a baked
/// primitive without the attributes, or one that names a model other than 0 (a mixed scene's file).
CompressedTransfer read_gltf_transfer(const std::string& path, std::vector<glm::vec3>* albedo);

}  // namespace prt::compress
