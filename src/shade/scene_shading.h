#pragma once
// Shading with split lighting (light/scene_lighting.h): the SH sky through the full transfer, the discs'
// direct light exactly (shade/disc_direct.h), and the discs' interreflected light through the transfer's
// bounce-only part (transfer::TransferData::bounce_only) applied to their exact SH projection:
//   L_o = T . L_sky + T_bounce . L_discs + direct(discs)
// (glossy: the same with matrices, then the BRDF, as shade/glossy.h). Without discs this is exactly
// shade_diffuse / shade_glossy_eye of the sky. Direct light follows the transfer's kind: no shadows for
// unshadowed transfer, Embree shadow rays otherwise. Unless the lighting was asked for unsplit and
// unwindowed (`--sun none --window none`, SceneLighting::clamp_negative) each channel is clamped at 0: what remains negative then is the Monte Carlo noise of fully occluded vertices (about
// 1e-4 of the lit radiance) and the band-limit's residue, never a colour. docs/conventions.md, "Sun and sky".
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "brdf/brdf.h"
#include "brdf/projection.h"
#include "brdf/vertex_brdfs.h"
#include "light/scene_lighting.h"
#include "mesh/mesh.h"
#include "shade/disc_direct.h"
#include "transfer/transfer_file.h"

namespace prt::trace {
class Scene;
}

namespace prt::shade {

/// What shading with discs could not do exactly, for a warning line (empty when all was exact).
struct SplitReport {
  std::string warning;
};

/// Diffuse transfer: per-vertex outgoing radiance under `lighting`. `origin` names the transfer in
/// errors and the warning. Throws prt::Error for a glossy transfer or mismatched sizes.
/// `shadow_scene`: the scene the discs' shadow rays are traced against; null: built from `mesh` (a
/// lightmap passes a mesh of texel sample points and the real scene). A transfer baked with
/// `--footprint area` (its parameters say so) gets its discs' shadow rays from the vertices'
/// footprints too (disc_direct.h), so all its terms are averages over the same surface.
std::vector<glm::vec3> shade_diffuse_split(const mesh::Mesh& mesh, const transfer::TransferData& transfer,
                                           const light::SceneLighting& lighting, const std::string& origin,
                                           const DiscShadingOptions& options = {}, SplitReport* report = nullptr,
                                           const trace::Scene* shadow_scene = nullptr);

/// Glossy transfer toward the eye point `eye` with BRDF `surface` (its matrix `matrix` at the transfer's
/// output bands).
std::vector<glm::vec3> shade_glossy_split(const mesh::Mesh& mesh, const transfer::TransferData& transfer,
                                          const brdf::Brdf& surface, const brdf::BrdfMatrix& matrix,
                                          const light::SceneLighting& lighting, const glm::vec3& eye,
                                          const std::string& origin, const DiscShadingOptions& options = {},
                                          SplitReport* report = nullptr);

/// As shade_glossy_split, each vertex v with its own BRDF brdfs.table[brdfs.of(v)]: a vertex's value
/// depends only on its own transfer and BRDF, so it is shade_glossy_split's with that BRDF alone.
std::vector<glm::vec3> shade_glossy_vertex_brdfs(const mesh::Mesh& mesh, const transfer::TransferData& transfer,
                                                 const brdf::VertexBrdfs& brdfs, const light::SceneLighting& lighting,
                                                 const glm::vec3& eye, const std::string& origin,
                                                 const DiscShadingOptions& options = {}, SplitReport* report = nullptr);

}  // namespace prt::shade
