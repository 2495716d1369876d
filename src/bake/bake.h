#pragma once
// Diffuse PRT baking (Sloan, Kautz and Snyder 2002): per-vertex transfer vectors T such that the
// outgoing radiance of vertex v under any distant lighting L (SH radiance coefficients, world frame) is
// sum_i T[v][i] L[i], per channel.
//
//   unshadowed:     T_lm = (albedo / pi) A_l Y_lm(n)              (closed form, Funk-Hecke; no rays)
//   shadowed:       T_i  = (albedo / pi) integral V(w) max(n.w, 0) Y_i(w) dw
//   interreflected: shadowed + sum over bounces b >= 1 of
//                   T^b(v) = (albedo_v / pi) integral_{w hits q} T^(b-1)(q) max(n.w, 0) dw
//                   (the series Le + T Le + T^2 Le + ... of the rendering equation, truncated).
//
// ESTIMATORS. Every vertex traces the same S directions: an Owen-scrambled Sobol set mapped to the
// cosine-weighted hemisphere (sh::hemisphere_directions_cosine(S, seed)), expressed in a per-vertex
// frame whose z axis is the vertex normal and whose rotation about it is a hash of (seed, vertex index),
// so neighbouring vertices do not share error patterns. With the cosine pdf, the shadowed transfer is
// estimated with the exact unshadowed transfer as a control variate:
//     T = T_unshadowed - (albedo / S) * sum over occluded samples s of Y(w_s),
// which is exact (zero noise) wherever nothing is occluded. The sum is accumulated in the local frame
// against a table of Y at the S local directions, then rotated to the world with the SH rotation.
// Bounce b gathers, for every sample whose ray hits the FRONT face of a triangle, the previous pass's
// transfer interpolated barycentrically at the hit point, and scales the sum by albedo / S. Back-face
// hits contribute nothing (single-sided surfaces; a closed mesh is never seen from inside).
//
// CHANNELS. If every vertex's albedo is grey (r = g = b) the transfer has one channel with the albedo
// folded in; otherwise three (RGB), so interreflection carries colour bleeding.
//
// DETERMINISM. Each vertex's result depends only on the mesh, the options and its index; the traced
// rays and every sum run in a fixed order. Output is byte-identical for any thread count, and for any
// number of ranks of a distributed bake (BakeOptions::dist; docs/distributed.md).
//
// GLOSSY (kinds glossy-shadowed, glossy-interreflected; Sloan, Kautz and Snyder 2002, section 6). Per
// vertex p a transfer MATRIX M_p (bands_out^2 x bands^2, row-major [out][in]) maps world lighting
// coefficients L to the coefficients T_p = M_p L of the transferred incident radiance in the vertex's
// LOCAL frame F_p = brdf::shading_frame(n_p) (brdf/frame.h). The surface's BRDF matrix B
// (brdf/projection.h, bands_out bands) then gives the outgoing radiance toward a view direction v:
//   L_o(p, v) = sum_k (B T_p)_k Y_k(F_p^T v)                     (shade/glossy.h).
//   glossy-shadowed:  T_p(w) = V'(F_p w) L(F_p w), where V' is the binary visibility above the tangent
//                     plane and 1 below it: the lower hemisphere is NOT masked, because B's factor
//                     max(cos theta_i, 0) removes it exactly (masking it would only add truncation
//                     ringing at the horizon). So an unoccluded vertex gets exactly M_p = Rot(F_p^T)
//                     (the lighting rotated into its frame), and with a Lambert B the result equals
//                     the diffuse bake's.
//                     M_p = integral over S^2 of V'(F_p w) y_out(w) y_in(w)^T dw Rot(F_p^T)
//                         = Rot(F_p^T) - (2 pi / S) Rot_out(F_p^T F_s) C Rot_in(F_s^T),
//                     C = sum over OCCLUDED samples s of y_out(w_s) y_in(w_s)^T, with S directions w_s
//                     uniform on the hemisphere (an Owen-scrambled Sobol set, pdf 1 / (2 pi)) in the
//                     sample frame F_s = sh::vertex_frame(n, seed, p) (the diffuse baker's hashed frame).
//                     The exact unoccluded part is the control variate: zero noise where nothing is
//                     occluded. C is summed in float, the rotations are applied in double.
//   bounce b >= 1:    T^b_p(w) = radiance arriving from front-face hits q along F_p w, where q's
//                     outgoing radiance toward p is sum_k (B M^(b-1)_q L)_k Y_k(F_q^T (-w)),
//                     interpolated barycentrically over the hit triangle's corners (each corner
//                     evaluated in its own frame); estimated with the same S uniform directions:
//                     M^b_p = (2 pi / S) Rot_out(F_p^T F_s) sum over front hits of y_out(w_s) r_s^T,
//                     r_s the hit's radiance row (world lighting -> radiance). Back faces are black.
//   glossy-interreflected = M^0 + M^1 + ... (bounces as for diffuse: a fixed count, or until a pass's
//                     energy sum_p,c M_p[0][0] falls below 1e-3 of the direct pass's).
// One BRDF (options.brdf) for the whole mesh, or with options.brdf_from_mesh each vertex's own, from its
// material (mesh_brdfs.h; a bounce's hit corner q is then shaded with q's BRDF B_q); the mesh's
// per-vertex albedo is not used. CHANNELS: glossy-shadowed has 1 (geometry only; the BRDF is applied
// when shading, so its transfer does not depend on the BRDFs); glossy-interreflected has 1 if every
// BRDF is grey, else 3 (the bounce light is coloured by the BRDF).
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "brdf/brdf.h"
#include "dist/context.h"
#include "mesh/mesh.h"
#include "mesh/vertex_footprint.h"
#include "mesh/writers.h"
#include "trace/scene.h"
#include "transfer/transfer_file.h"

namespace prt::bake {

struct BakeOptions {
  transfer::Kind kind = transfer::Kind::shadowed;  ///< any kind; glossy kinds need `brdf`
  int bands = 5;                                   ///< 1..kMaxBands (lighting, input side)
  int samples = 1024;                              ///< rays per vertex, >= 1 (shadowed, interreflected)
  int bounces = -1;       ///< interreflection passes; -1: until a pass adds < 1e-3 of the first pass's energy (cap 16)
  glm::vec3 albedo{0.8f}; ///< linear albedo in [0,1] for meshes that carry none
  /// The user gave `albedo` (the caller has dropped the mesh's own, mesh::drop_albedo): the bake
  /// parameters record its source as "option" rather than the default.
  bool albedo_given = false;
  std::uint32_t seed = 1; ///< sample-set scrambling and per-vertex frame rotations
  int threads = 0;        ///< worker threads; 0 = all cores. Does not change the output.
  bool progress = false;  ///< progress bar on stderr (only drawn when stderr is a terminal)
  brdf::Brdf brdf;        ///< glossy kinds: the BRDF of the whole mesh (required unless brdf_from_mesh); unused otherwise
  /// Glossy kinds: each vertex's BRDF from the mesh's materials (mesh_brdfs.h; `brdf` unused). The mesh
  /// must have materials.
  bool brdf_from_mesh = false;
  int bands_out = 0;      ///< glossy kinds: transferred-radiance bands 1..bands; 0 = bands
  /// Where each vertex's rays leave from (shadowed, interreflected and glossy kinds): `area`, points
  /// spread over the vertex's one-ring with its hat weight, so that the value stored is the average
  /// that linear interpolation stands for (no dark vertex at a crease that only the vertex itself
  /// sees, no dark foot where an object stands on another; docs/conventions.md "Vertex footprint", the
  /// default of `prt bake`); `vertex`, the vertex itself (the radiance exactly at the vertex, what
  /// `prt reference` estimates per vertex by default).
  mesh::Footprint footprint = mesh::Footprint::vertex;
  /// The ranks of a distributed bake (dist/context.h); null: this process alone. Every rank traces its
  /// share of the vertices and the passes' results are exchanged. Rank 0's result is complete
  /// (byte-identical to a single process's); so is every rank's for the interreflected kinds (every
  /// pass is allgathered); otherwise the other ranks' values are undefined.
  const dist::Context* dist = nullptr;
};

/// What the bake did and measured (not stored in the file, which must not depend on timing).
struct BakeReport {
  int bounces_done = 0;
  std::vector<double> pass_energy;   ///< per pass (0 = direct): sum over vertices and channels of T[0]
  std::uint64_t rays_traced = 0;    ///< by all ranks together
  double seconds_build = 0, seconds_visibility = 0, seconds_bounces = 0;
  std::vector<std::string> notes;   ///< one-line notes for the user (e.g. mesh_brdfs's)
};

/// The automatic bounce rule: stop after the first pass whose energy is below this fraction of pass 0's.
inline constexpr double kBounceEnergyThreshold = 1e-3;
inline constexpr int kMaxAutoBounces = 16;

/// Throws prt::Error naming the option if `options` is out of range (what bake() checks first).
void validate_options(const BakeOptions& options);

/// Bakes `mesh` (vertices, normals, optional albedo; see mesh/mesh.h) into a transfer of
/// options.kind. Throws prt::Error for invalid options (bands, samples, bounces out of range, a glossy
/// kind without a BRDF, bands_out out of range). The header carries the mesh's counts and fingerprint
/// and the bake parameters as JSON (glossy: also "bands_out", "brdf" (brdf::to_spec) and "frame").
transfer::TransferData bake(const mesh::Mesh& mesh, const BakeOptions& options, BakeReport* report = nullptr);

/// The ray scene of the vertex bakes (bake, bake_glossy): `threads` build threads, RTC_SCENE_FLAG_ROBUST
/// off, rays spawned with the origin pullback that keeps robust mode's answers (trace/scene.h, ROBUST
/// MODE; docs/conventions.md, "Robust mode").
trace::SceneOptions bake_scene_options(int threads);

/// Bytes that the bounce passes' base colour lookups hold for `mesh` (HitColours, passes.h: the mip
/// pyramids of its textures, mesh::TextureMips::coarse_bytes, and one lookup per triangle); 0 unless
/// its bounce hits read textures (albedo_at_hits). For the memory checks of interreflected bakes.
std::uint64_t hit_colour_bytes(const mesh::Mesh& mesh);

/// Per-vertex albedo the bake uses: the mesh's own, or options.albedo for every vertex.
std::vector<glm::vec3> effective_albedo(const mesh::Mesh& mesh, const glm::vec3& fallback);

}  // namespace prt::bake
