#pragma once
// What the exact (disc) direct term needs to know of a transfer's bake: the diffuse albedo per vertex
// (a 1-channel transfer has it folded in) and where the vertices' rays left from.
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/mesh.h"
#include "mesh/vertex_footprint.h"
#include "transfer/transfer_file.h"

namespace prt::shade {

/// Whether a transfer was baked with the mesh's own albedo: its bake parameters say "albedo": "mesh", or
/// name no albedo and the mesh carries one. (A bake with --albedo says [r, g, b]: the renderer then
/// shows no texture, docs/conventions.md "Albedo and textures".)
bool baked_with_mesh_albedo(const mesh::Mesh& mesh, const transfer::Header& header);

/// Per-vertex linear albedo in [0,1]: the mesh's own when its bake parameters say "albedo": "mesh" (or
/// the mesh carries albedo and the parameters name none), else the bake's fallback albedo, the
/// parameters' "albedo": [r, g, b]. Transfers without either (hand-made files) get 0.8 grey, the bake's
/// default. Throws prt::Error("<what>: ...") if the parameters say "mesh" but the mesh has no albedo,
/// or the albedo entry is malformed.
std::vector<glm::vec3> surface_albedo(const mesh::Mesh& mesh, const transfer::Header& header, const std::string& what);

/// The footprint a transfer was baked with: its parameters' "footprint" ("area" or "vertex"), vertex
/// when absent. Throws prt::Error("<what>: bake parameters: ...") for another value.
mesh::Footprint baked_footprint(const transfer::Header& header, const std::string& what);

}  // namespace prt::shade
