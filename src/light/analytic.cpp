#include "light/analytic.h"

#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "core/error.h"
#include "sh/basis.h"
#include "sh/zonal.h"

namespace prt::light {

namespace {

void check_bands(const char* light, int bands) {
  if (bands < 1 || bands > sh::kMaxBands)
    fail(std::string(light) + ": bands must be in [1, " + std::to_string(sh::kMaxBands) + "], got " +
         std::to_string(bands));
}

glm::dvec3 unit_direction(const char* light, const glm::dvec3& direction) {
  const double length = glm::length(direction);
  if (!(length > 0.0) || !std::isfinite(length))
    fail(std::string(light) + ": the direction must be finite and non-zero");
  return direction / length;
}

// Coefficients colour * sh[i] for a scalar SH function sh[0..bands^2).
sh::RgbCoefficients coloured(int bands, const double* scalar, const glm::dvec3& colour) {
  sh::RgbCoefficients out(bands);
  for (int i = 0; i < bands * bands; ++i) out.values[i] = scalar[i] * colour;
  return out;
}

}  // namespace

double directional_light_scale(int bands) {
  // Exit radiance facing the light = E(d) / pi = scale * sum_l A_l sum_m Y_lm(d)^2 / pi, and
  // sum_m Y_lm(d)^2 = (2l+1) / (4 pi) (addition theorem).
  double facing = 0.0;
  for (int l = 0; l < bands; ++l) facing += sh::clamped_cosine_factor(l) * (2.0 * l + 1.0) / (4.0 * M_PI);
  return M_PI / facing;
}

sh::RgbCoefficients directional_light(int bands, const glm::dvec3& direction, const glm::dvec3& colour) {
  check_bands("directional light", bands);
  const glm::dvec3 d = unit_direction("directional light", direction);
  double basis[sh::kMaxBands * sh::kMaxBands];
  sh::eval(bands, d, basis);
  return coloured(bands, basis, directional_light_scale(bands) * colour);
}

namespace {

// Cap zonal coefficients from cos a, sin^2 a and 1 - cos a, each passed exactly (see cap_zonal).
void cap_zonal_from(int bands, double cos_a, double sin2_a, double one_minus_cos_a, double* zonal) {
  zonal[0] = 2.0 * M_PI * std::sqrt(1.0 / (4.0 * M_PI)) * one_minus_cos_a;
  for (int l = 1; l < bands; ++l) {
    // integral_c^1 P_l = (1 - c^2) P_l'(c) / (l (l+1)), from the Legendre equation
    // ((1 - t^2) P_l')' = -l (l+1) P_l integrated over [c, 1]; equal to (P_(l-1) - P_(l+1)) / (2l+1).
    const double integral = sin2_a * sh::legendre_derivative(l, cos_a) / (l * (l + 1.0));
    zonal[l] = 2.0 * M_PI * std::sqrt((2.0 * l + 1.0) / (4.0 * M_PI)) * integral;
  }
}

}  // namespace

void cap_zonal(int bands, double half_angle_radians, double* zonal) {
  const double s = std::sin(half_angle_radians), half_s = std::sin(0.5 * half_angle_radians);
  // 1 - cos a = 2 sin^2(a/2): no cancellation for small a.
  cap_zonal_from(bands, std::cos(half_angle_radians), s * s, 2.0 * half_s * half_s, zonal);
}

sh::RgbCoefficients cone_light(int bands, const glm::dvec3& direction, double half_angle_radians,
                               const glm::dvec3& radiance) {
  check_bands("cone light", bands);
  const glm::dvec3 d = unit_direction("cone light", direction);
  if (!(half_angle_radians > 0.0 && half_angle_radians <= M_PI))
    fail("cone light: the half angle must be in (0, pi] radians, got " + std::to_string(half_angle_radians));
  double zonal[sh::kMaxBands];
  cap_zonal(bands, half_angle_radians, zonal);
  double scalar[sh::kMaxBands * sh::kMaxBands];
  sh::zonal_to_sh(bands, zonal, d, scalar);
  return coloured(bands, scalar, radiance);
}

sh::RgbCoefficients hemisphere_light(int bands, const glm::dvec3& up, const glm::dvec3& sky,
                                     const glm::dvec3& ground) {
  check_bands("hemisphere light", bands);
  const glm::dvec3 d = unit_direction("hemisphere light", up);
  double zonal[sh::kMaxBands];
  cap_zonal_from(bands, 0.0, 1.0, 1.0, zonal);  // the half angle pi/2, exactly
  double scalar[sh::kMaxBands * sh::kMaxBands];
  sh::zonal_to_sh(bands, zonal, d, scalar);
  sh::RgbCoefficients out = coloured(bands, scalar, sky - ground);
  out.values[0] += 2.0 * std::sqrt(M_PI) * ground;
  return out;
}

sh::RgbCoefficients constant_light(int bands, const glm::dvec3& radiance) {
  check_bands("constant light", bands);
  sh::RgbCoefficients out(bands);
  out.values[0] = 2.0 * std::sqrt(M_PI) * radiance;
  return out;
}

}  // namespace prt::light
