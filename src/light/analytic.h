#pragma once
// Analytic distant lights as SH radiance coefficients. Directions are unit world vectors pointing
// TOWARD the light (from the receiver); colours are linear RGB. Every function throws prt::Error for
// bands outside [1, kMaxBands], a zero or non-finite direction (directions need not be unit: they are
// normalised here) or an out-of-range angle.
#include <glm/vec3.hpp>

#include "sh/coefficients.h"

namespace prt::light {

/// A directional light, normalised so that a Lambert surface of albedo 1 facing it has exit radiance
/// `colour` when the light is band-limited to `bands` (the DirectXMath XMSHEvalDirectionalLight
/// convention): coefficients Y_i(d) * colour * pi / sum_l A_l (2l+1)/(4 pi), with A_l the clamped
/// cosine's factors (sh/zonal.h). The scale is 4 pi for 1 band, 4 pi / 3 for 2, 16 pi / 17 for 3 and 4,
/// 32 pi / 31 for 5 and 6 bands.
sh::RgbCoefficients directional_light(int bands, const glm::dvec3& direction, const glm::dvec3& colour);

/// The scale above: pi / sum_{l < bands} A_l (2l+1) / (4 pi). Precondition: 1 <= bands <= kMaxBands.
double directional_light_scale(int bands);

/// Uniform radiance `radiance` inside the cone of half-angle `half_angle_radians` (0, pi] about
/// `direction`, zero outside. Exact zonal coefficients of the cap, rotated to the direction:
///   z_0 = 2 pi Y_00 (1 - cos a),
///   z_l = 2 pi K_l integral_{cos a}^1 P_l(t) dt = 2 pi K_l (P_(l-1)(cos a) - P_(l+1)(cos a)) / (2l+1)
///       = 2 pi K_l sin^2(a) P_l'(cos a) / (l (l+1))   (l >= 1, K_l = sqrt((2l+1)/(4 pi))),
/// evaluated in the last form, which does not cancel for small a.
sh::RgbCoefficients cone_light(int bands, const glm::dvec3& direction, double half_angle_radians,
                               const glm::dvec3& radiance);

/// The zonal coefficients z_0..z_(bands-1) of the indicator of the cap of half-angle `half_angle_radians`
/// about +z (unit radiance), as above. Precondition: 1 <= bands, half angle in [0, pi].
void cap_zonal(int bands, double half_angle_radians, double* zonal);

/// Sky + ground: radiance `sky` over the hemisphere about `up`, `ground` over the other one
/// (= ground everywhere plus (sky - ground) in a cap of half-angle pi/2).
sh::RgbCoefficients hemisphere_light(int bands, const glm::dvec3& up, const glm::dvec3& sky,
                                     const glm::dvec3& ground);

/// Constant radiance in every direction: only c_0 = 2 sqrt(pi) * radiance is non-zero.
sh::RgbCoefficients constant_light(int bands, const glm::dvec3& radiance);

}  // namespace prt::light
