#pragma once
// Outgoing radiance of the scene's surfaces, per vertex: what a probe ray that hits a surface sees
// (interpolated barycentrically at the hit point).
//
// DEFINITION. With G the diffuse gather operator (G f)(v) = albedo_v / pi * integral over the
// hemisphere of v of f(first front-face hit along w) cos dw (back-face hits and escaping rays give 0),
// E_m the emission and D(v) = albedo_v / pi * (E_env(v) + E_sun(v)) the direct reflection of the
// environment and the sun with visibility, the surface radiance after K interreflection bounces is
//     R_0 = E_m + D,     R_k = E_m + D + G R_(k-1),     k = 1..K.
// So a probe that sees R_K receives light that was diffusely reflected up to K + 1 times (emitters
// light other surfaces from the first bounce on, through G).
//
// ESTIMATORS. Every vertex traces the same S cosine-distributed directions (an Owen-scrambled Sobol
// set), turned about its normal by a hashed angle; rays start at Scene::offset_origin(p, n).
//   E_env = E_sh(n) + (pi / S) sum_s [V_s L_env(w_s) - L_sh(w_s)]
// with L_sh the environment's 5-band SH projection and E_sh(n) its closed-form unoccluded irradiance:
// a control variate that is exact where nothing occludes and the environment is band-limited. A vertex
// with more than half of 16 PILOT occlusion rays blocked (their own cosine-distributed Sobol set, turned
// by their own hashed angle, so independent of the S rays) uses plain Monte Carlo instead,
// (pi / S) sum over its escaping rays of L_env (no basis evaluations), and leaves E_sh(n) out. Choosing
// from the S rays' own hit count would bias the estimate (the choice would correlate with the
// quadrature error of the control variate). L_env is looked up in lookup_environment(environment)
// (lighting.h).
//   E_sun = L_sun * Omega / M * sum_k V_k max(n . w_k, 0)
// over M stratified directions w_k uniform in the sun's disc. G uses the S rays again: (pi / S) sum
// over front-face hits of f at the hit.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "core/hash.h"
#include "dist/context.h"
#include "mesh/mesh.h"
#include "probes/lighting.h"

namespace prt::trace {
class Scene;
}

namespace prt::probes {

struct SurfaceOptions {
  int samples = 256;       ///< S, hemisphere rays per vertex, 1..65536
  int sun_samples = 16;    ///< M, shadow rays per vertex toward the sun's disc, 1..4096
  int bounces = 2;         ///< K, interreflection bounces, 0..64
  bool environment = true; ///< include the environment in D (false: sun and emission only)
  std::uint32_t seed = 1;
  int threads = 0;
  bool progress = false;
  const dist::Context* dist = nullptr;  ///< ranks of a distributed run (each traces a share); null: this process
};

/// R_K of every vertex (mesh order), linear RGB radiance. `albedo` has one entry per vertex;
/// light.emission is empty or has one entry per vertex. Returns the rays traced in `rays` if given.
std::vector<glm::vec3> surface_radiance(const trace::Scene& scene, const mesh::Mesh& mesh,
                                        const std::vector<glm::vec3>& albedo, const SceneLight& light,
                                        const SurfaceOptions& options, std::uint64_t* rays = nullptr);

using prt::hash_to_unit;  // core/hash.h: the per-vertex and per-probe rotation angles and scrambles

}  // namespace prt::probes
