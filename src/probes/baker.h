#pragma once
// Probe baking: incident radiance SH at points in a scene, with visibility and interreflected light.
//
// WHAT A PROBE STORES. For probe position p and direction w, the incident radiance is
//     L_in(p, w) = L_env(w)                    if the ray p + t w escapes,
//                = R_K(x) interpolated          if it first meets the FRONT face of a triangle at x,
//                = 0                           if it first meets a BACK face (inside geometry),
// plus the sun's disc where it is visible from p (R_K: surface.h). The probe holds
//     c_i = integral over the sphere of L_in(p, w) Y_i(w) dw,   i < bands^2 (prt basis, world frame).
//
// ESTIMATOR. The S ray directions are an Owen-scrambled Sobol set on the sphere
// (sh::sphere_directions(S, seed)) turned by a random rotation hashed from (seed, probe index); sums are
// formed in that rotated frame against a table of Y at the set's directions and rotated to the world
// with the SH rotation. Rays are traced in batches of up to 256. Each probe first traces 16 PILOT
// occlusion rays (another Sobol set under another hashed rotation) and from them picks one of two
// unbiased estimators for all its S rays, whichever needs fewer environment lookups:
//   at most half the pilot rays blocked (control variate):  c_env + (4 pi / S) sum over hit rays of
//                                                           (L_hit - L_env(w_s)) Y(w_s),
//   more than half blocked (plain):                         (4 pi / S) sum over all rays of L_in(p, w_s) Y(w_s),
// where c_env is the exact projection of the environment image (light::project). A probe in open space
// is therefore exactly c_env (noise comes only from the blocked directions), and a probe in a closed
// room looks up the environment only through its openings.
// The choice depends only on the pilot rays, which are independent of the S rays, so the estimate stays
// unbiased; a choice made from the S rays' own hit count would not be (a batch with fewer hits than
// usual would take the control variate exactly when its quadrature error has one sign).
// The sun adds c_sun V_sun: c_sun the exact SH of its disc (lighting.h), V_sun the unoccluded fraction of
// `sun_samples` stratified shadow rays.
//
// VALIDITY. backface_fraction = (rays whose first hit is a back face) / S. A probe with
// backface_fraction > max_backface_fraction is inside geometry: marked invalid (its coefficients are
// still stored, as computed).
//
// TRANSFER (Sloan et al. 2002, "neighborhood transfer"). With transfer_bands = B, per probe a matrix
// M (bands^2 x B^2, per channel) and bias b such that c ~= M L + b for environment SH L (B bands):
//     M_ij = delta_ij + (4 pi / S) sum over hit rays of Y_i(w_s) (T_j(x_s) [front] - Y_j(w_s)),
// with T the per-vertex interreflected transfer of prt::bake (kind interreflected, B bands, the same
// bounces K and samples S_surface) interpolated at the hit; b is the bake above with the environment
// switched off (sun and emission with their bounces). M L + b differs from c only because M sees the
// environment band-limited to B bands (in blocked directions and in the surfaces' lighting).
//
// DETERMINISM. Each probe's result depends only on the inputs, the options and its index: identical
// for any thread count.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "dist/context.h"
#include "mesh/mesh.h"
#include "probes/lighting.h"
#include "probes/probe_set.h"

namespace prt::probes {

struct ProbeBakeOptions {
  int bands = 3;                 ///< probe SH bands, 1..16
  int rays = 1024;               ///< S, rays per probe, 1..1048576
  int bounces = 2;               ///< K interreflection bounces of the surfaces (surface.h), 0..64
  int surface_samples = 256;     ///< hemisphere rays per scene vertex for the surface radiance
  int sun_samples = 16;          ///< shadow rays toward the sun's disc per vertex and per probe
  double max_backface_fraction = 0.5;  ///< above it a probe is invalid
  int transfer_bands = 0;        ///< 0: no transfer; else B, 1..8
  glm::vec3 albedo{0.8f};        ///< for meshes without albedo
  std::uint32_t seed = 1;
  int threads = 0;               ///< 0: all cores; does not change the output
  bool progress = false;
  /// Ranks of a distributed bake (dist/context.h); null: this process alone. The surface passes and the
  /// probes are split over the ranks; only rank 0's result is complete (the others' is undefined).
  const dist::Context* dist = nullptr;
};

/// What the bake measured (timing is not part of the output).
struct ProbeBakeReport {
  double seconds_build = 0, seconds_surface = 0, seconds_probes = 0, seconds_transfer = 0;
  /// CPU time of the whole process (all threads) during the probe pass: robust to a busy machine.
  double cpu_seconds_probes = 0;
  std::uint64_t surface_rays = 0, probe_rays = 0, transfer_rays = 0;
  std::size_t invalid = 0;
};

/// Throws prt::Error naming the option for any option out of range.
void check_options(const ProbeBakeOptions& options);

/// Bytes `probe_count` probes need at most with these options: the positions (given and stored), the
/// coefficients, validity and back-face fractions, the transfer matrices and bias (three channels),
/// twice over for the copy an export makes. For the memory check before the bake.
std::uint64_t estimated_bytes(std::uint64_t probe_count, const ProbeBakeOptions& options);

/// Bakes probes at `positions` (layout and grid copied into the result from `layout`, which also gives
/// the layout type). `light.emission` is empty or one per mesh vertex. Throws prt::Error for invalid
/// options or inputs.
ProbeSet bake_probes(const mesh::Mesh& mesh, const SceneLight& light, const std::vector<glm::dvec3>& positions,
                     const ProbeSet& layout, const ProbeBakeOptions& options, ProbeBakeReport* report = nullptr);

/// Applies a probe set's transfer to environment SH `environment` (any bands; truncated or zero-padded
/// to transfer_bands): coefficients = M L + bias for every probe; the sky becomes L (its first
/// min(bands, transfer_bands) bands) + sky_bias (the sun, unchanged); transfer_environment becomes L.
/// Throws prt::Error if the set has no transfer.
void relight(ProbeSet& probes, const sh::RgbCoefficients& environment);

}  // namespace prt::probes
