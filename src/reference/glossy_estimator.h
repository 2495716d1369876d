#pragma once
// The reference path tracer for glossy surfaces (`prt reference --brdf SPEC --eye X,Y,Z`): the outgoing
// radiance of a mesh vertex TOWARD A VIEW DIRECTION, for one BRDF on the whole mesh (brdf/brdf.h), under
// a distant environment, with visibility and interreflection. Shares the environment sampler, the
// sample streams and the ray rules (offsets, front faces) with the Lambertian estimator (estimator.h);
// the only SH it uses is the band-limited BRDF, when asked for.
//
// WHAT IS ESTIMATED. At a surface point x with shading normal n, local frame F = brdf::shading_frame(n),
// toward the view direction v (world, unit), with b bounces left:
//   L_o(x, v, b) = integral over the sphere of L_i(x, w, b) rho(F^T w, F^T v) dw,
// with the cosine-weighted BRDF rho either
//   TRUE:          rho(w_i, w_o) = fbar(w_i, w_o) max(w_i.z, 0)  (0 below the horizon), or
//   BAND-LIMITED:  rho(w_i, w_o) = sum_kj B_kj Y_j(w_i) Y_k(w_o)  (brdf::reconstruct of the BRDF matrix B
//                  of N bands; signed, and non-zero below the horizon),
// and the incident radiance
//   L_i(x, w, b) = L_env(w)        if w points below the tangent plane (n . w <= 0): NOT traced. Only the
//                                  band-limited rho is non-zero there; this is exactly what glossy PRT
//                                  computes (bake.h, GLOSSY: the lower hemisphere is left unmasked, the
//                                  true BRDF's cosine removes it);
//                = L_env(w)        if the ray from x along w escapes;
//                = L_o(q, -w, b-1) if it first hits the FRONT face of a triangle at q and b > 0 (normal
//                                  interpolated at q, as estimator.h);
//                = 0               otherwise.
// With the band-limited BRDF of bands_out bands, a band-limited environment and b = 0 (1) this is what
// `prt bake --transfer glossy-shadowed` (glossy-interreflected --bounces 1) + `prt shade --eye` predict,
// up to the baker's noise and its interpolation of outgoing radiance at bounce hits.
//
// ESTIMATOR (the loop of path_loop.h, shared with the Lambertian estimator). At each path vertex: one environment sample (next-event estimation; a shadow ray only
// above the tangent plane) and one BRDF sample, combined by the power heuristic. The BRDF sample is
//   - at the vertex being estimated, with the band-limited BRDF: SIGN-AWARE tabulated sampling: the
//     density is proportional to |rho_BL(., v)| tabulated on a 64 x 32 equirect grid of the local sphere
//     (the cells of EnvironmentSampler over that table), mixed with 10% uniform sphere sampling; the
//     weight rho / pdf carries rho's sign;
//   - elsewhere: LobeSampler (brdf_sampling.h) about the local view direction, with 30% uniform sphere
//     sampling for the band-limited BRDF (its ringing reaches every direction) and none for the true one.
// A path continues from a front-face hit above the tangent plane while bounces remain, with throughput
// multiplied by rho / pdf (signed); Russian roulette from depth kRouletteDepth on |throughput|.
// At a point on one triangle (a hit, a footprint point) the true-surface rule holds (trace/true_surface.h):
// a direction above the tangent plane but below the triangle's plane carries no light (as in the glossy
// bake's passes, which block such rays).
// DETERMINISM: as estimator.h (per-estimate SampleStream, fixed summation order).
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "brdf/brdf.h"
#include "brdf/projection.h"
#include "mesh/mesh.h"
#include "reference/environment_sampler.h"
#include "reference/estimator.h"
#include "reference/reference.h"
#include "trace/scene.h"

namespace prt::reference {

struct GlossyEstimatorOptions {
  int bounces = 0;          ///< interreflection bounces after the vertex estimated
  brdf::Brdf brdf;          ///< the surface BRDF (non-empty)
  int brdf_bands = 0;       ///< 0: the true BRDF; N in 1..32: the band-limited BRDF of N bands
};

/// Scratch memory for glossy estimates; one per thread, reused. Not thread-safe.
class GlossyWorkspace {
 public:
  GlossyWorkspace();
  ~GlossyWorkspace();
  GlossyWorkspace(const GlossyWorkspace&) = delete;
  GlossyWorkspace& operator=(const GlossyWorkspace&) = delete;
  struct Buffers;
  Buffers& buffers() { return *buffers_; }

 private:
  std::unique_ptr<Buffers> buffers_;
};

/// The glossy estimator over one mesh, its scene and an environment (references kept: they must
/// outlive it). Methods are const and may run concurrently with one workspace and stream per thread.
class GlossyTracer {
 public:
  /// Throws prt::Error for an empty BRDF or brdf_bands outside 0..32. Precondition: unit normals,
  /// `scene` built from `mesh`.
  GlossyTracer(const mesh::Mesh& mesh, const trace::Scene& scene, const EnvironmentSampler& environment,
               const GlossyEstimatorOptions& options);
  ~GlossyTracer();

  /// L_o(vertex, view, options.bounces) (see above) from `paths` >= 1 paths; `view` unit, world frame.
  /// The paths leave from `position` (the vertex's own, or a point of its footprint) lifted along the
  /// vertex normal (Scene::offset_origin); normal and shading frame are the vertex's. `triangle`: the
  /// mesh triangle a footprint point lies on (its true-surface rule, trace/true_surface.h);
  /// mesh::kNoTriangle for the vertex itself.
  RadianceEstimate vertex_radiance(std::uint32_t vertex, const glm::vec3& position, const glm::dvec3& view, int paths,
                                   SampleStream& stream, GlossyWorkspace& workspace,
                                   std::uint32_t triangle = mesh::kNoTriangle) const;

 struct Impl;  // the BRDF, its matrix and lobe sampler (internal)

 private:
  std::unique_ptr<Impl> impl_;
};

/// What `prt reference --brdf SPEC --eye X,Y,Z` does: options of the per-vertex run.
struct GlossyReferenceOptions {
  GlossyEstimatorOptions estimator;  ///< bounces, BRDF, band limit of the BRDF
  int samples = kDefaultSamples;     ///< paths per vertex, 1..kMaxSamples
  std::uint32_t seed = 1;            ///< vertex v uses SampleStream(seed, v)
  int threads = 0;                   ///< worker threads; 0 = all cores. Does not change the output.
  bool progress = false;
  glm::dvec3 eye{0.0};               ///< the eye point (mesh units): view = normalize(eye - position)
  const dist::Context* dist = nullptr;  ///< ranks of a distributed run (reference.h, ReferenceOptions::dist)
  mesh::Footprint footprint = mesh::Footprint::vertex;  ///< as ReferenceOptions::footprint; the view stays the vertex's
};

/// Glossy options with the run settings of `shared` (samples, seed, footprint, threads, progress, dist);
/// the estimator (BRDF, bounces) and the eye are left to the caller.
GlossyReferenceOptions glossy_run_options(const ReferenceOptions& shared);

/// Outgoing radiance of every vertex toward the eye point (a vertex exactly at the eye uses its
/// normal), in mesh vertex order, visiting vertices in Morton order with a BVH built on one thread:
/// bit-identical for any thread count. Throws prt::Error for bounces or samples out of range (as
/// check_options), an empty BRDF or brdf_bands out of range.
std::vector<glm::vec3> glossy_vertex_radiance(const mesh::Mesh& mesh, const EnvironmentSampler& environment,
                                              const GlossyReferenceOptions& options, ReferenceReport* report = nullptr,
                                              std::vector<glm::vec3>* standard_error = nullptr);

}  // namespace prt::reference
