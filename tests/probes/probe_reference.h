#pragma once
// An independent Monte Carlo reference for probe baking: a brute-force path tracer of the incident
// radiance at a point, projected onto SH by plain Monte Carlo. It shares only the ray queries
// (prt::trace, Embree) and the environment lookup with the probe baker: no SH rotation, no sample sets,
// no per-vertex precomputation, no control variates, no interpolation of radiance.
//
// It estimates exactly what src/probes/baker.h defines, with surface radiance R_K of surface.h, but at
// the true hit point instead of interpolated from vertices:
//   L_in(p, w) = L_env(w) on escape, 0 on a back face, L_o(x, K) on a front face at x,
//   L_o(x, k)  = E_m(x) + albedo(x)/pi * E_sun(x) + albedo(x) * [escape: L_env(w') | front hit y, k >= 1:
//                L_o(y, k - 1) | otherwise 0] for one cosine-distributed w' (the environment's direct
//                light and the k-th bounce share that one ray),
//   E_sun(x)   = L_sun * Omega * max(n . w_s, 0) * V(w_s) for one uniform sample w_s of the disc,
// and c_i = (4 pi / N) sum_j Y_i(w_j) L_in(p, w_j) + L_sun Omega / N sum_j Y_i(s_j) V(s_j) for N
// uniform directions w_j and N uniform disc samples s_j. Normals, albedo and emission at x are the
// barycentric interpolation of the vertex values (normals renormalised).
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "light/environment.h"
#include "mesh/mesh.h"
#include "probes/lighting.h"
#include "sh/coefficients.h"

namespace prt::test {

struct ReferenceProbe {
  sh::RgbCoefficients coefficients;
  sh::RgbCoefficients standard_error;  ///< per coefficient, i.i.d. estimate
  double backface_fraction = 0.0;
};

std::vector<ReferenceProbe> reference_probes(const mesh::Mesh& mesh, const std::vector<glm::vec3>& albedo,
                                             const std::vector<glm::vec3>& emission, const light::Environment* environment,
                                             const std::optional<probes::Sun>& sun, const std::vector<glm::dvec3>& positions,
                                             int bands, int bounces, int paths, std::uint32_t seed, int threads = 0);

}  // namespace prt::test
