// The `gltf:` BRDF against the glTF 2.0 specification's metallic-roughness model (Appendix B),
// written out here on its own: mix(fresnel_mix(ior 1.5, diffuse, specular), conductor_fresnel(base,
// specular), metallic), with diffuse = baseColor / pi, specular = D V (Trowbridge-Reitz D; V the
// height-correlated Smith term prt documents in brdf/brdf.h, Filament's form, where the specification's
// sample code uses the separable one), Schlick's Fresnel with the spec's VdotH.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include <glm/geometric.hpp>

#include "brdf/brdf.h"

using namespace prt;

namespace {

// glTF Appendix B, channel by channel, for unit w_i, w_o in the upper hemisphere.
glm::dvec3 gltf_reference(const glm::dvec3& base, double metallic, double roughness, const glm::dvec3& l, const glm::dvec3& v) {
  const glm::dvec3 h = glm::normalize(l + v);
  const double alpha = roughness * roughness, a2 = alpha * alpha;
  const double n_h = h.z, n_l = l.z, n_v = v.z, v_h = std::abs(glm::dot(v, h));
  const double d = a2 / (M_PI * std::pow(n_h * n_h * (a2 - 1.0) + 1.0, 2.0));
  const double vis = 0.5 / (n_v * std::sqrt(n_l * n_l * (1.0 - a2) + a2) + n_l * std::sqrt(n_v * n_v * (1.0 - a2) + a2));
  const double specular = d * vis;
  const double schlick = std::pow(1.0 - v_h, 5.0);
  glm::dvec3 out;
  for (int c = 0; c < 3; ++c) {
    const double f_dielectric = 0.04 + (1.0 - 0.04) * schlick;
    const double dielectric = (1.0 - f_dielectric) * base[c] / M_PI + f_dielectric * specular;  // fresnel_mix
    const double metal = (base[c] + (1.0 - base[c]) * schlick) * specular;                         // conductor_fresnel
    out[c] = (1.0 - metallic) * dielectric + metallic * metal;
  }
  return out;
}

glm::dvec3 random_upper(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double z = 0.02 + 0.98 * u(rng), phi = 2.0 * M_PI * u(rng), r = std::sqrt(1.0 - z * z);
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// Directional albedo integral f(w_i, w_o) cos(theta_o) dw_o by a fine midpoint product rule.
double albedo(const brdf::Brdf& b, const glm::dvec3& w_i) {
  const int nt = 400, np = 400;
  double sum = 0.0;
  for (int a = 0; a < nt; ++a)
    for (int p = 0; p < np; ++p) {
      const double t = (a + 0.5) * (M_PI / 2) / nt, phi = (p + 0.5) * 2.0 * M_PI / np;
      const glm::dvec3 w_o(std::sin(t) * std::cos(phi), std::sin(t) * std::sin(phi), std::cos(t));
      sum += brdf::eval(b, w_i, w_o).r * std::cos(t) * std::sin(t) * (M_PI / 2 / nt) * (2.0 * M_PI / np);
    }
  return sum;
}

}  // namespace

TEST_CASE("gltf BRDF is the glTF specification's model with fresnel_mix on the diffuse lobe", "[brdf]") {
  std::mt19937_64 rng(11);
  for (const auto& [base, metallic, roughness] : {std::tuple{glm::dvec3(0.8, 0.2, 0.1), 0.25, 0.4},
                                                   std::tuple{glm::dvec3(1.0), 0.0, 1.0}, std::tuple{glm::dvec3(0.5, 0.9, 0.3), 0.0, 0.15},
                                                   std::tuple{glm::dvec3(1.0, 0.8, 0.3), 1.0, 0.35}}) {
    char spec[160];
    std::snprintf(spec, sizeof spec, "gltf:basecolor=%g/%g/%g,metallic=%g,roughness=%g", base.r, base.g, base.b, metallic, roughness);
    const brdf::Brdf b = brdf::parse_brdf(spec);
    INFO(spec);
    for (int k = 0; k < 500; ++k) {
      const glm::dvec3 l = random_upper(rng), v = random_upper(rng);
      const glm::dvec3 want = gltf_reference(base, metallic, roughness, l, v), got = brdf::eval(b, l, v);
      for (int c = 0; c < 3; ++c) CHECK(got[c] == Approx(want[c]).epsilon(1e-10).margin(1e-14));
    }
    // The canonical spec keeps the fresnel_mix lobe.
    CHECK(brdf::to_spec(brdf::parse_brdf(brdf::to_spec(b))) == brdf::to_spec(b));
  }
}

TEST_CASE("gltf BRDF: a white rough dielectric reflects at most all the light and less toward grazing", "[brdf]") {
  const brdf::Brdf b = brdf::parse_brdf("gltf:basecolor=1,metallic=0,roughness=1");
  const double normal = albedo(b, {0, 0, 1});
  const double grazing = albedo(b, {std::sin(1.5), 0.0, std::cos(1.5)});
  CHECK(normal <= 1.0);
  CHECK(grazing <= 1.0);
  // Grazing light: the diffuse lobe gives way to the Fresnel reflection, (1 - F) -> 0 as F -> 1.
  const glm::dvec3 l(std::sin(1.55), 0.0, std::cos(1.55)), v(-std::sin(1.55), 0.0, std::cos(1.55));
  const brdf::Brdf diffuse_only = brdf::parse_brdf("lambert:albedo=1,fresnel_mix=1");
  CHECK(brdf::eval(diffuse_only, l, v).r < 0.96 / M_PI);
  CHECK(brdf::eval(diffuse_only, {0, 0, 1}, {0, 0, 1}).r == Approx(0.96 / M_PI).epsilon(1e-12));
  CHECK_THROWS_WITH(brdf::parse_brdf("lambert:albedo=0.5,fresnel_mix=2"), Catch::Contains("fresnel_mix must be 0 or 1"));
}
