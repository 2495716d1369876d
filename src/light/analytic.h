#pragma once
// Analytic distant lights as SH radiance coefficients. Directions are unit world vectors pointing
// TOWARD the light (from the receiver); colours are linear RGB.
#include <glm/vec3.hpp>

#include "sh/coefficients.h"

namespace prt::light {

/// A directional light, normalised so that a Lambert surface of albedo 1 facing it has exit radiance
/// `colour` when the light is band-limited to `bands` (the DirectXMath XMSHEvalDirectionalLight
/// convention): coefficients Y_i(d) * colour * pi / sum_l A_l (2l+1)/(4 pi). E.g. 16 pi / 17 for 3 bands.
sh::RgbCoefficients directional_light(int bands, const glm::dvec3& direction, const glm::dvec3& colour);

/// Uniform radiance `radiance` inside the cone of half-angle `half_angle_radians` (0, pi] about
/// `direction`, zero outside. Exact zonal coefficients rotated to the direction.
sh::RgbCoefficients cone_light(int bands, const glm::dvec3& direction, double half_angle_radians,
                               const glm::dvec3& radiance);

/// Sky + ground: radiance `sky` over the hemisphere about `up`, `ground` over the other one.
sh::RgbCoefficients hemisphere_light(int bands, const glm::dvec3& up, const glm::dvec3& sky,
                                     const glm::dvec3& ground);

/// Constant radiance in every direction: only c_0 = 2 sqrt(pi) * radiance is non-zero.
sh::RgbCoefficients constant_light(int bands, const glm::dvec3& radiance);

}  // namespace prt::light
