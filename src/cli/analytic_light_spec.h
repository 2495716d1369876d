#pragma once
// Analytic lights as `prt light` inputs: a spec string in place of the environment map, projected
// exactly (light/analytic.h) instead of being sampled. Grammar (terms joined with '+' add up):
//   directional:DX,DY,DZ:R,G,B          toward-light direction; R,G,B = exit radiance of an albedo-1
//                                       Lambert surface facing it, at the chosen band count
//                                       (DirectXMath's normalisation, docs/conventions.md)
//   cone:DX,DY,DZ:DEGREES:R,G,B         radiance R,G,B inside the cone of half-angle DEGREES (0, 180]
//   hemisphere:UX,UY,UZ:R,G,B:R,G,B     sky radiance over the hemisphere about U, ground radiance below
//   constant:R,G,B                      the same radiance in every direction
// Directions need not be unit length; numbers are finite decimals without '+' (which separates
// terms: write 1e3, not 1e+3). Example:
//   prt light 'directional:0,1,0:3,3,3+constant:0.1,0.1,0.1' -o L.json --bands 5
#include <string>

#include <glm/vec3.hpp>

#include "light/scene_lighting.h"
#include "sh/coefficients.h"

namespace prt::cli {

/// True if `text` starts with one of "directional:", "cone:", "hemisphere:", "constant:".
bool is_analytic_light_spec(const std::string& text);

/// The SH radiance coefficients (`bands` bands, prt basis, world frame) of the sum of the spec's terms.
/// Throws prt::Error("<term>: <problem>") naming the bad term (unknown kind, wrong field count, a bad
/// number, a zero direction, an angle outside (0, 180]).
sh::RgbCoefficients analytic_light_coefficients(const std::string& spec, int bands);

/// The spec's lights as `prt light` writes them: analytic_light_coefficients rotated by the active
/// rotation Ry(yaw) Rx(pitch) Rz(roll) (`yaw_pitch_roll` in degrees), no discs, no window (exact).
light::SceneLighting analytic_scene_lighting(const std::string& spec, int bands, const glm::dvec3& yaw_pitch_roll);

}  // namespace prt::cli
