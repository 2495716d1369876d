#pragma once
// The reference path tracer's radiance estimator: outgoing radiance of a Lambertian surface point lit
// by a distant environment, with visibility and interreflection, by Monte Carlo path tracing. It shares
// only the mesh and the ray queries (prt::trace) with the baker: no transfer, no SH.
//
// WHAT IS ESTIMATED. For a surface point x with shading normal n and albedo rho, and b bounces left,
//   L_o(x, b) = (rho / pi) * integral over the sphere of L_i(x, w, b) max(n.w, 0) dw,
//   L_i(x, w, b) = L_env(w)       if the ray from x along w escapes (EnvironmentSampler::radiance),
//                = L_o(q, b - 1)  if it first hits the FRONT face of a triangle at q and b > 0,
//                = 0              otherwise (b = 0 and something is hit; or a BACK face is hit).
// Front face: the triangle's geometric normal ng = (p1 - p0) x (p2 - p0) of its counter-clockwise
// corners faces the ray (ng . w < 0); back faces are black, single-sided surfaces as in the baker.
// At a point on one triangle (a hit, a footprint or texel point; not a mesh vertex) the true-surface
// rule holds (trace/true_surface.h): directions with ng . w <= 0 carry no light (the integrand is 0
// there: neither strategy traces them, a BSDF sample there ends its path).
// At a hit point q: position, shading normal (normalised) and albedo are interpolated barycentrically
// from the triangle's corners (Embree's u, v); on a textured mesh (Mesh::textured) the albedo at q is
// the base colour there, mesh::base_color (docs/conventions.md, "Albedo and textures"). A mesh vertex
// as the estimated point (vertex_point, and the footprint points of reference.h) keeps the vertex's
// albedo, Mesh::albedo: the per-vertex estimate is albedo_v times the footprint's mean irradiance / pi,
// the quantity prt shade predicts from the transfer, not the mean of albedo(x) E(x) / pi over the
// footprint that a renderer multiplying the texture per pixel shows. So with b = 0 this is direct lighting with binary
// visibility (what the baker's shadowed transfer predicts), and each bounce adds one interreflection.
//
// ESTIMATOR (pbrt's path tracer with next-event estimation, Veach's multiple importance sampling; the
// loop is path_loop.h, shared with the glossy estimator, with the Lambertian BRDF as its surface model).
// At every surface vertex of a path, with throughput beta (product of albedos, divided by roulette
// survival probabilities):
//  1. Environment sample (next-event estimation): w_l from EnvironmentSampler::sample (density p_l);
//     if n.w_l > 0 and a shadow ray from the vertex escapes, add
//        beta * rho * L_env(w_l) * (n.w_l / pi) / p_l * m_l,   m_l = p_l^2 / (p_l^2 + p_b^2),
//     with p_b = max(n.w_l, 0) / pi the BSDF sampling density (power heuristic, exponent 2).
//  2. BSDF sample: w_b cosine-distributed about n (sh::square_to_hemisphere_cosine, p_b = n.w_b / pi),
//     so the Lambert factor rho (n.w / pi) / p_b is rho. The ray is traced:
//       - it escapes: add beta * rho * L_env(w_b) * m_b, m_b = p_b^2 / (p_b^2 + p_l(w_b)^2);
//       - it hits a front face and bounces are left: the path continues at the hit point with
//         beta *= rho (the environment is the only emitter, so nothing is added at the hit itself);
//       - otherwise the path ends.
//  3. Russian roulette from surface depth kRouletteDepth on (the vertex or pixel hit is depth 0):
//     the path survives with probability q = min(1, max component of beta) and beta /= q. The
//     estimator stays unbiased; the fixed bounce limit b still truncates the series exactly there.
// Radiance is used with its sign (band-limited environments ring negative); every term is linear in it.
// The estimate is the mean over `paths` independent paths.
//
// SAMPLE POINTS. Each estimate draws from a SampleStream: the 2D points of every path vertex (the
// environment sample and the BSDF sample) are points of independently Owen-scrambled Sobol sequences
// (sh::sobol_2d, index = path number, one seed per depth and pair), which stratifies every bounce
// (randomised quasi-Monte Carlo: still unbiased); Russian roulette uses the stream's PCG32.
//
// RAY OFFSETS (the baker's rule, trace/scene.h). Rays from a mesh vertex start at
// Scene::offset_origin(p, n) with the vertex normal n; rays from a hit point start at
// q + ng_unit * Scene::ray_offset(), on the front side of the hit triangle; tnear = 0.
//
// BATCHING. The paths of one estimate advance together, up to kPathsPerWave at a time: all their
// shadow rays go to Embree in one occlusion call, all their BSDF rays in one closest-hit call (an
// occlusion call at the last bounce, where only escaping matters).
//
// DETERMINISM. An estimate depends only on the scene, the point, `paths`, the options and the stream's
// state: the paths are generated and summed in a fixed order on the calling thread.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "mesh/mesh.h"
#include "reference/environment_sampler.h"
#include "sh/sampling.h"
#include "trace/scene.h"
#include "trace/true_surface.h"

namespace prt::reference {

/// Surface depth (0 = the point being estimated) from which Russian roulette may end paths.
inline constexpr int kRouletteDepth = 3;
/// Paths traced together (one shadow batch and one continuation batch of this many rays).
inline constexpr int kPathsPerWave = 256;

/// The random numbers of one estimate (one vertex, one pixel): the PCG32 stream `stream` of `seed`
/// (Russian roulette), and per path depth two Owen-scrambled Sobol 2D sequences indexed by the path
/// number (the environment sample and the BSDF sample of that depth), each scrambled and shuffled with
/// its own seed, hashed from the stream's first output, the depth and the pair (Burley 2020's padding:
/// independently scrambled 2D sequences make the points of all dimensions together uniformly
/// distributed, so the estimate stays unbiased while every bounce is stratified).
class SampleStream {
 public:
  SampleStream(std::uint64_t seed, std::uint64_t stream);
  sh::Rng& rng() { return rng_; }
  /// Scrambling seed of the 2D sequence for surface depth `depth` (>= 0); pair 0: environment sample,
  /// pair 1: BSDF sample.
  std::uint32_t dimension_seed(int depth, int pair) const;

 private:
  sh::Rng rng_;
  std::uint32_t base_seed_;
};

/// A point of a surface as the estimator uses it.
struct SurfacePoint {
  glm::dvec3 normal{0.0, 1.0, 0.0};  ///< unit shading normal: the hemisphere integrated over
  glm::dvec3 origin{0.0};            ///< where rays leave the surface (offset rule above)
  glm::dvec3 albedo{0.0};            ///< linear diffuse reflectance per channel, in [0, 1]
  trace::TrueSurface surface{};      ///< the true-surface rule there (none at a mesh vertex)
};

/// A Monte Carlo estimate and the usual (i.i.d.) estimate of its standard error, per channel:
/// sqrt(sample variance of the per-path values / paths). With the stratified first bounce the true
/// error is usually smaller than this.
struct RadianceEstimate {
  glm::dvec3 value{0.0};
  glm::dvec3 standard_error{0.0};
  std::uint64_t rays = 0;  ///< rays traced for it
};

/// The mean of `paths` (>= 1) path values from their sum and sum of squares, with its i.i.d. standard
/// error (0 for one path), carrying `rays` along.
RadianceEstimate mean_estimate(const glm::dvec3& sum, const glm::dvec3& sum_sq, int paths, std::uint64_t rays);

struct EstimatorOptions {
  int bounces = 0;  ///< interreflection bounces after the point estimated; 0 = direct lighting only
};

/// Scratch memory for estimates (ray batches, path states); one per thread, reused. Not thread-safe.
class PathWorkspace {
 public:
  PathWorkspace();
  ~PathWorkspace();
  PathWorkspace(const PathWorkspace&) = delete;
  PathWorkspace& operator=(const PathWorkspace&) = delete;

  struct Buffers;
  Buffers& buffers() { return *buffers_; }

 private:
  std::unique_ptr<Buffers> buffers_;
};

/// The estimator over one mesh, its ray scene and an environment. Holds references: the mesh, albedo,
/// scene and sampler must outlive it. All methods are const and may run concurrently, each thread with
/// its own PathWorkspace and SampleStream.
class PathTracer {
 public:
  /// `albedo`: one linear albedo per mesh vertex (see reference_albedo in reference.h).
  /// Preconditions: the mesh has unit normals, albedo.size() == vertex count, `scene` built from `mesh`.
  PathTracer(const mesh::Mesh& mesh, const std::vector<glm::vec3>& albedo, const trace::Scene& scene,
             const EnvironmentSampler& environment, const EstimatorOptions& options);

  /// Mesh vertex v as a surface point: its normal, Scene::offset_origin(position, normal), its albedo.
  SurfacePoint vertex_point(std::uint32_t vertex) const;

  /// The surface point where a ray along `direction` hit, or false if it hit a back face (or missed).
  bool hit_point(const trace::HitResult& hit, const glm::vec3& direction, SurfacePoint& point) const;

  /// L_o(point, options.bounces) (see above) from `paths` >= 1 paths: the Lambertian surface's outgoing
  /// radiance, the same toward every direction.
  RadianceEstimate outgoing_radiance(const SurfacePoint& point, int paths, SampleStream& stream,
                                     PathWorkspace& workspace) const;

  /// Radiance arriving at `origin` from the ray origin + t direction (t > 0): the environment's if the
  /// ray escapes; the outgoing radiance of the first hit (estimated with `paths` paths, options.bounces
  /// bounces) if that is a front face; 0 on a back face. This is what a camera pixel sees.
  RadianceEstimate incoming_radiance(const glm::dvec3& origin, const glm::dvec3& direction, int paths,
                                     SampleStream& stream, PathWorkspace& workspace) const;

  const EstimatorOptions& options() const { return options_; }

 private:
  const mesh::Mesh& mesh_;
  const std::vector<glm::vec3>& albedo_;
  const trace::Scene& scene_;
  const EnvironmentSampler& environment_;
  EstimatorOptions options_;
};

}  // namespace prt::reference
