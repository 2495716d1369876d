#pragma once
// `prt reference`: the ground truth for the baker. Per mesh vertex v it estimates by path tracing the
// outgoing radiance
//   L_o(v) = (albedo_v / pi) * integral over the sphere of L_i(v, w) max(n_v . w, 0) dw
// of a Lambertian surface under a distant environment, with visibility and `bounces` interreflection
// bounces (estimator.h says exactly what L_i is and how it is sampled). It is what `prt bake` +
// `prt shade` predict for the same environment: bounces = 0 matches the shadowed transfer,
// bounces = K the interreflected transfer with --bounces K; with band_limited_environment(env, N)
// it matches a bake with N bands exactly in expectation, so any difference is the baker's error (its
// noise, interpolation at bounce hits) plus this estimate's noise.
//
// `prt reference --image` renders the same estimate per pixel, seen by the camera of `prt render`
// (reference_image.h).
//
// Shared with the baker: only the mesh loader (prt::mesh) and the ray queries (prt::trace, with the
// same ray offset rule and the same front-face test). No transfer code; SH appears only in
// band_limited_environment, never in the estimator. Glossy surfaces (`--brdf SPEC --eye X,Y,Z`) have
// their own estimator, glossy_estimator.h, which uses prt::brdf's BRDFs and, for the band-limited BRDF
// only, its SH matrix.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "dist/context.h"
#include "light/environment.h"
#include "mesh/mesh.h"
#include "mesh/vertex_footprint.h"
#include "reference/environment_sampler.h"

namespace prt::reference {

/// Paths per vertex of `prt reference` unless --samples is given. Chosen for about a minute on 2 cores
/// for 10k vertices with the default (direct) lighting: measured 1.8 Mpaths/s per core (11,003 vertices,
/// box with blocks under a sky with a sun lobe; shared, busy machine), i.e. ~50 s of CPU per core, for
/// a relative noise of 0.05% (rel_rms of one run against the exact answer, from two seeds). Noise falls
/// faster than 1/sqrt(samples) (stratified first bounce): 0.44% at 1024, 0.16% at 4096 there. With
/// bounces a path costs more (~2.5x at 2 bounces) and the noise is higher (0.5% at 8192, 2 bounces).
inline constexpr int kDefaultSamples = 16384;
/// Largest --samples and --bounces accepted.
inline constexpr int kMaxSamples = 1 << 24;
inline constexpr int kMaxBounces = 64;

struct ReferenceOptions {
  int bounces = 0;              ///< interreflection bounces, 0..kMaxBounces (0 = direct with visibility)
  int samples = kDefaultSamples;  ///< paths per vertex, 1..kMaxSamples
  glm::vec3 albedo{0.8f};       ///< linear albedo in [0,1] for meshes that carry none
  std::uint32_t seed = 1;       ///< vertex v uses SampleStream(seed, v)
  int threads = 0;              ///< worker threads; 0 = all cores. Does not change the output.
  bool progress = false;        ///< progress bar on stderr (only drawn when stderr is a terminal)
  const dist::Context* dist = nullptr;  ///< ranks of a distributed run (only rank 0's result is complete); null: this process
  /// vertex_radiance: `area`, the hat-weighted average over each vertex's one-ring, what a bake with the
  /// same footprint stores (paths from points of the footprint, vertex_driver.h footprint_estimate);
  /// `vertex`, the radiance exactly at the vertex. point_radiance ignores it.
  mesh::Footprint footprint = mesh::Footprint::vertex;
};

/// What a run did (timing is not part of the output).
struct ReferenceReport {
  std::uint64_t paths = 0;
  std::uint64_t rays = 0;
  double seconds_build = 0.0;  ///< BVH build
  double seconds_trace = 0.0;  ///< the estimates
  /// Mean over vertices of the relative i.i.d. standard error (standard_error / |value|, channels
  /// averaged, vertices with |value| below 1e-6 of the maximum skipped): a rough noise figure.
  double mean_relative_standard_error = 0.0;
};

/// Per-vertex albedo: the mesh's own if it has any, else `fallback` for every vertex (the same rule as
/// the baker; see mesh/mesh.h ALBEDO).
std::vector<glm::vec3> reference_albedo(const mesh::Mesh& mesh, const glm::vec3& fallback);

/// Throws prt::Error naming the option for bounces, samples or albedo out of range.
void check_options(const ReferenceOptions& options);

/// Outgoing radiance of every vertex, in the mesh's vertex order, by path tracing (estimator.h) in the
/// environment of `environment`, at each vertex or over its footprint (options.footprint). Vertices are
/// visited in Morton order, in parallel chunks; each uses SampleStream(options.seed, v) (footprint: its
/// runs' streams, footprint_estimate) and sums its paths in a fixed order, and the BVH is built with one
/// thread, so the result is bit-identical for any thread count. `standard_error` (optional) receives
/// the per-vertex i.i.d. standard error estimates. Throws prt::Error for invalid options.
std::vector<glm::vec3> vertex_radiance(const mesh::Mesh& mesh, const EnvironmentSampler& environment,
                                       const ReferenceOptions& options, ReferenceReport* report = nullptr,
                                       std::vector<glm::vec3>* standard_error = nullptr);

/// A surface point given explicitly (a lightmap texel's sample point): position, unit normal, albedo,
/// and the mesh triangle it lies on (the true-surface rule, trace/true_surface.h; mesh::kNoTriangle:
/// no rule).
struct PointSample {
  glm::vec3 position{0.0f}, normal{0.0f, 1.0f, 0.0f}, albedo{0.8f};
  std::uint32_t triangle = mesh::kNoTriangle;
};

/// Outgoing radiance at each of `points` on the surface of `mesh`, estimated as vertex_radiance does
/// for vertices (rays from Scene::offset_origin(position, normal); bounce hits use the mesh's
/// interpolated albedo), point k with SampleStream(options.seed, k). Bit-identical for any thread count.
std::vector<glm::vec3> point_radiance(const mesh::Mesh& mesh, const EnvironmentSampler& environment,
                                      const ReferenceOptions& options, const std::vector<PointSample>& points,
                                      ReferenceReport* report = nullptr);

/// Height in pixels of the equirect image band_limited_environment renders for `bands` bands:
/// max(256, 16 * bands), width twice that. Why this is fine enough: the reconstruction is looked up
/// bilinearly between texel centres (Environment::radiance); for a band-limited function the
/// interpolation error is about (h^2 / 8) |d^2 L / d angle^2| <= (h^2 / 8) l (l + 1) |L_l| for the
/// highest band l = bands - 1 and texel size h = pi / height: at most 1.4e-3 |L_l| up to 9 bands
/// (h = pi / 256) and 4.7e-3 |L_l| up to 32 bands (h = pi / 512), and it mostly averages out in the
/// cosine-weighted integral. Measured (tests/reference, a bright disc plus a sky truncated to 5 and 9
/// bands): the integral of the rendered image against max(n.w, 0) differs from the closed form
/// (Funk-Hecke) by 5.0e-5 (5 bands) and 2.9e-5 (9 bands) of the largest irradiance, far below 1%; a
/// smaller image also keeps the importance-sampling tables in cache.
int band_limited_height(int bands);

/// The environment reconstructed from its first `bands` SH bands: light::project(environment, bands)
/// rendered with light::render_equirect at 2 band_limited_height(bands) x band_limited_height(bands).
/// Signed (ringing makes it negative in places). Throws prt::Error("--band-limit: ...") unless
/// 1 <= bands <= sh::kMaxBands.
light::Environment band_limited_environment(const light::Environment& environment, int bands, int threads = 0);

}  // namespace prt::reference
