#include "probes/engine_sh.h"

#include <cmath>

#include "core/constants.h"
#include "sh/zonal.h"

namespace prt::probes {

namespace {


// |K_i| of the polynomial form Y_i = +-K_i P_i (docs/conventions.md's table, in closed form).
const std::array<double, 9> kBasisConstant{{
    0.5 * std::sqrt(1.0 / kPi),                                                          // 0: 1
    std::sqrt(3.0 / (4.0 * kPi)), std::sqrt(3.0 / (4.0 * kPi)), std::sqrt(3.0 / (4.0 * kPi)),  // y z x
    0.5 * std::sqrt(15.0 / kPi), 0.5 * std::sqrt(15.0 / kPi),                           // xy yz
    0.25 * std::sqrt(5.0 / kPi),                                                         // 3z^2-1
    0.5 * std::sqrt(15.0 / kPi), 0.25 * std::sqrt(15.0 / kPi)}};                         // xz x^2-y^2

std::array<double, 9> make_clamped_cosine() {
  std::array<double, 9> a{};
  for (int i = 0; i < 9; ++i) a[i] = sh::clamped_cosine_factor(i == 0 ? 0 : (i < 4 ? 1 : 2));
  return a;
}

std::array<double, 9> make_polynomial_factor() {
  std::array<double, 9> pf{};
  const std::array<double, 9> a = make_clamped_cosine();
  for (int i = 0; i < 9; ++i) pf[i] = a[i] / kPi * kBasisConstant[i];
  return pf;
}

}  // namespace

const std::array<double, 9> kClampedCosineFactor = make_clamped_cosine();
const std::array<double, 9> kIrradiancePolynomialFactor = make_polynomial_factor();

// x -> -x: the x, xy and xz terms change sign (in both the CS and the non-CS basis).
constexpr std::array<double, 9> kMirrorX{{1, 1, 1, -1, -1, 1, 1, -1, 1}};

Sh9 first_nine(const sh::RgbCoefficients& c) {
  Sh9 out{};
  for (std::size_t i = 0; i < 9 && i < c.values.size(); ++i) out[i] = c.values[i];
  return out;
}

Sh9 threejs_coefficients(const sh::RgbCoefficients& c) {
  Sh9 out = first_nine(c);
  for (int i = 0; i < 9; ++i) out[i] *= kCondonShortleySign[i];
  return out;
}

Sh9 godot_coefficients(const sh::RgbCoefficients& c) {
  Sh9 out = threejs_coefficients(c);
  for (glm::dvec3& v : out) v /= kPi;
  return out;
}

Sh9 unity_coefficients(const sh::RgbCoefficients& c) {
  Sh9 out = threejs_coefficients(c);
  for (int i = 0; i < 9; ++i) out[i] *= kIrradiancePolynomialFactor[i] * kMirrorX[i];
  return out;
}

glm::dvec3 to_unity_frame(const glm::dvec3& p) { return {-p.x, p.y, p.z}; }

Sh9 filament_coefficients(const sh::RgbCoefficients& c) {
  Sh9 out = threejs_coefficients(c);
  for (int i = 0; i < 9; ++i) out[i] *= kIrradiancePolynomialFactor[i];
  return out;
}

Sh9 gltf_irradiance_coefficients(const sh::RgbCoefficients& c) {
  Sh9 out = first_nine(c);
  for (int i = 0; i < 9; ++i) out[i] *= kClampedCosineFactor[i] * kMirrorX[i];
  return out;
}

std::array<glm::dvec3, 6> bevy_ambient_cube(const sh::RgbCoefficients& c) {
  const Sh9 p = filament_coefficients(c);
  return {{p[0] + p[3] - p[6] + p[8], p[0] - p[3] - p[6] + p[8], p[0] + p[1] - p[6] - p[8],
           p[0] - p[1] - p[6] - p[8], p[0] + p[2] + 2.0 * p[6], p[0] - p[2] + 2.0 * p[6]}};
}

glm::dvec3 irradiance_over_pi(const sh::RgbCoefficients& c, const glm::dvec3& normal) {
  return sh::irradiance(c.bands >= 3 ? c.truncated(3) : c, normal) / kPi;
}

}  // namespace prt::probes
