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
// rays and every sum run in a fixed order. Output is byte-identical for any thread count.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/mesh.h"
#include "mesh/writers.h"
#include "transfer/transfer_file.h"

namespace prt::bake {

struct BakeOptions {
  transfer::Kind kind = transfer::Kind::shadowed;  ///< a diffuse kind
  int bands = 5;                                   ///< 1..kMaxBands
  int samples = 1024;                              ///< rays per vertex, >= 1 (shadowed, interreflected)
  int bounces = -1;       ///< interreflection passes; -1: until a pass adds < 1e-3 of the first pass's energy (cap 16)
  glm::vec3 albedo{0.8f}; ///< linear albedo in [0,1] for meshes that carry none
  std::uint32_t seed = 1; ///< sample-set scrambling and per-vertex frame rotations
  int threads = 0;        ///< worker threads; 0 = all cores. Does not change the output.
  bool progress = false;  ///< progress bar on stderr (only drawn when stderr is a terminal)
};

/// What the bake did and measured (not stored in the file, which must not depend on timing).
struct BakeReport {
  int bounces_done = 0;
  std::vector<double> pass_energy;   ///< per pass (0 = direct): sum over vertices and channels of T[0]
  std::uint64_t rays_traced = 0;
  double seconds_build = 0, seconds_visibility = 0, seconds_bounces = 0;
};

/// The automatic bounce rule: stop after the first pass whose energy is below this fraction of pass 0's.
inline constexpr double kBounceEnergyThreshold = 1e-3;
inline constexpr int kMaxAutoBounces = 16;

/// Throws prt::Error naming the option if `options` is out of range (what bake() checks first).
void validate_options(const BakeOptions& options);

/// Bakes `mesh` (vertices, normals, optional albedo; see mesh/mesh.h) into a transfer of
/// options.kind. Throws prt::Error for invalid options (bands, samples, bounces out of range, a glossy
/// kind). The header carries the mesh's counts and fingerprint and the bake parameters as JSON.
transfer::TransferData bake(const mesh::Mesh& mesh, const BakeOptions& options, BakeReport* report = nullptr);

/// Per-vertex albedo the bake uses: the mesh's own, or options.albedo for every vertex.
std::vector<glm::vec3> effective_albedo(const mesh::Mesh& mesh, const glm::vec3& fallback);

/// Packs a diffuse transfer into vec4 vertex attributes "_PRT_T0", "_PRT_T1", ... for write_glb:
/// channel-major, coefficients in index order, 4 per attribute, the last one zero-padded
/// (docs/formats.md, "Transfer in glTF").
std::vector<mesh::VertexAttribute> pack_transfer_attributes(const transfer::TransferData& transfer);

}  // namespace prt::bake
