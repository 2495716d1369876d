#pragma once
// The direct light of discs (light/disc.h: a sun, lamps) at mesh vertices, computed exactly on the CPU:
// the reference that the renderer's shadow-mapped disc term is measured against.
//
// For vertex p (position x_p, unit normal n_p) and disc D (radiance L, solid angle Omega), with the
// S = k^2 stratified directions w_s of the disc (light::disc_direction_sample at the stratum centres
// ((i + 0.5) / k, (j + 0.5) / k): uniform in solid angle):
//   diffuse:  L_o = (albedo_p / pi) L (Omega / S) sum_s V(x_p, w_s) max(n_p . w_s, 0)
//   glossy:   L_o = L (Omega / S) sum_s V(x_p, w_s) fbar(F^T w_s, F^T v) max(n_p . w_s, 0)
//             (brdf::eval_cosine in the vertex's shading frame F = brdf::shading_frame(n_p), v toward
//             the eye)
// V is 1 when the ray from scene.offset_origin(x_p, n_p) toward w_s meets no triangle (either side), or
// always 1 without a scene (unshadowed transfer). For a small disc fully above the horizon and
// unoccluded, the diffuse term is (albedo / pi) E (n . d) (light/disc.h).
// With footprints (a transfer baked with --footprint area), ray s of vertex p leaves from the footprint
// point VertexFootprints::stratified_point(p, s, hash_to_u32(seed, p, kDiscFootprintSalt)) instead of
// x_p (lifted the same way): V is averaged over the surface that the vertex's value covers, as the
// bake's sky and bounce terms are (docs/conventions.md "Vertex footprint").
// THE TRUE-SURFACE RULE (trace/true_surface.h): a shadow ray from a point on one triangle (a footprint
// point, or a point with DiscShadingOptions::geometric_normals) below that triangle's plane counts as
// occluded, as the bake's direct pass counts it.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "brdf/brdf.h"
#include "light/disc.h"
#include "mesh/mesh.h"
#include "mesh/vertex_footprint.h"

namespace prt::trace {
class Scene;
}

namespace prt::shade {

struct DiscShadingOptions {
  int samples = 64;  ///< S per disc, rounded up to a square k^2; 1..65536
  int threads = 0;   ///< 0: all cores; the result does not depend on it
  /// The mesh's vertex footprints, or null: rays leave from the vertices themselves (see above).
  const mesh::VertexFootprints* footprints = nullptr;
  std::uint32_t seed = 1;  ///< scrambles the footprint points
  /// Points that lie on one triangle each (a lightmap's texel samples passed as a mesh of points): the
  /// unit geometric normal of each point's triangle, one per vertex of the mesh shaded; null: none.
  /// With it, or with footprints, the true-surface rule holds (below).
  const std::vector<glm::vec3>* geometric_normals = nullptr;
};

/// Salt of the hash that scrambles a vertex's footprint points for disc rays (core/hash.h).
inline constexpr std::uint32_t kDiscFootprintSalt = 0xd15c0000u;

/// Diffuse direct light of `discs` per vertex (linear RGB). `albedo` one per vertex; `scene` built from
/// `mesh`, or nullptr for no shadows. Throws prt::Error if the sizes differ or samples is out of range.
std::vector<glm::vec3> disc_direct_diffuse(const mesh::Mesh& mesh, const std::vector<glm::vec3>& albedo,
                                           const std::vector<light::Disc>& discs, const trace::Scene* scene,
                                           const DiscShadingOptions& options = {});

/// Glossy direct light of `discs` per vertex toward `view` (unit, world, from the vertex toward the
/// viewer; one per vertex) with the BRDF `surface`. As disc_direct_diffuse otherwise.
std::vector<glm::vec3> disc_direct_glossy(const mesh::Mesh& mesh, const brdf::Brdf& surface,
                                          const std::vector<light::Disc>& discs, const std::vector<glm::vec3>& view,
                                          const trace::Scene* scene, const DiscShadingOptions& options = {});

/// The fraction of each vertex's S stratified disc rays (as above) that reach `disc` unoccluded,
/// counting only rays above the vertex's tangent plane (1 when none is). For measuring shadow maps.
std::vector<float> disc_visibility(const mesh::Mesh& mesh, const light::Disc& disc, const trace::Scene& scene,
                                   const DiscShadingOptions& options = {});

}  // namespace prt::shade
