#pragma once
// Loading a mixed scene (transfer/mixed_parts.h; docs/conventions.md "Mixed scenes"): a texel transfer
// file for some parts and a per-vertex file for the others, baked together, which the renderer draws in
// one frame (Renderer::add_mixed: the per-vertex pass draws its triangles, the lightmap pass the others).
#include <cstdint>
#include <string>
#include <vector>

#include "render/triangle_runs.h"
#include "render/scene_inputs.h"

namespace prt::render {

/// The transfer files to load for `path`: {path} for a file of one kind; for a .prt of a mixed pair,
/// the texel file then the per-vertex file (whichever of them `path` is). Throws prt::Error naming the
/// file for a malformed "mixed" entry or a partner that cannot be read.
std::vector<std::string> mixed_transfer_paths(const std::string& path);

/// The runs of triangles a mixed scene draws per vertex, from the "mixed" entries of
/// scene.transfers[texel] and scene.transfers[texel + 1] (the texel file then the per-vertex file, as
/// loaded from mixed_transfer_paths). Throws prt::Error naming the file if the two files' entries or
/// kinds do not make a pair (texel then vertex, the same per-vertex triangles) or a run leaves the mesh.
TriangleRuns mixed_vertex_runs(const SceneInputs& scene, std::size_t texel = 0);

}  // namespace prt::render
